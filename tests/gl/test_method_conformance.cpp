// test_method_conformance.cpp: what every registered method must do, checked over the registry (a new method is
// tested by registering it): on a small scene (a sphere of skim-milk-like material lit from the side, with the
// method's quick_settings) the output is finite and not blank, the same for the same seed, its passes and
// statistics are the ones it declares, a bad parameter value is one clear error naming the parameter, and the mean
// radiance over the sphere agrees with the CPU bssrdf reference within the tolerance the method declares. Where methods
// are weakest, each method is compared per pixel with its reference (bssrdf, or volpath for a method that estimates
// it) on the sphere, a thin slab lit from behind and a coarse box lit obliquely, within the tolerances it declares
// (MethodInfo::weakest) beside the values it measured.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "image_compare.h"
#include "lucent/lucent.h"
#include "methods/method_info.h"
#include "reference/reference_files.h"
#include "reference/reference_renderer.h"

namespace {

constexpr int kSize = 48;

// `method_keys`: the "method" object's keys besides "name" (JSON text without braces); by default the method's
// quick_settings.
std::string scene_json(const lucent::methods::MethodInfo& method, std::string method_keys = "-") {
  if (method_keys == "-") {
    std::string quick(method.quick_settings);
    method_keys = quick.substr(quick.find('{') + 1, quick.rfind('}') - quick.find('{') - 1);
  }
  bool empty = method_keys.find_first_not_of(" ") == std::string::npos;
  return fmt::format(R"({{
    "scale_mm": 1,
    "camera": {{ "eye": [0, 0, 6], "target": [0, 0, 0], "fov_y_deg": 24 }},
    "lights": [{{ "direction": [-0.8, -0.3, -0.5], "radiance": [1, 1, 1] }}],
    "objects": [{{ "shape": "sphere", "radius": 1, "segments": 64,
                  "material": {{ "sigma_a": [0.05, 0.08, 0.12], "sigma_s": [2.0, 2.2, 2.5], "g": 0, "eta": 1.3 }} }}],
    "method": {{ "name": "{}"{}{} }},
    "render": {{ "width": {}, "height": {}, "frames": 2, "seed": 7 }} }})",
                     method.name, empty ? "" : ", ", method_keys, kSize, kSize);
}

struct Rendered {
  lucent::ImageRGBA32F radiance;
  lucent::FrameTimings last;
};

Rendered render(const lucent::Scene& scene) {
  lucent::OffscreenFramebuffer framebuffer(kSize, kSize);
  lucent::Renderer renderer(scene);
  for (int f = 0; f < scene.render.frames; ++f) renderer.render(scene.camera, {framebuffer.id(), kSize, kSize});
  return {renderer.read_radiance(), renderer.last_frame_timings()};
}

// Mean of r, g, b over the pixels where the sphere is (alpha = 1 in the method's output).
double mean_over_object(const lucent::ImageRGBA32F& image, const lucent::ImageRGBA32F& mask, int* count = nullptr) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
    if (mask.pixels[i + 3] <= 0.5f) continue;
    sum += (image.pixels[i] + image.pixels[i + 1] + image.pixels[i + 2]) / 3.0;
    ++n;
  }
  if (count) *count = n;
  return n > 0 ? sum / n : 0.0;
}

class MethodConformance : public ::testing::TestWithParam<const lucent::methods::MethodInfo*> {};

TEST_P(MethodConformance, RendersFiniteNonBlankDeterministicAndDeclared) {
  const lucent::methods::MethodInfo& method = *GetParam();
  lucent::test::ensure_gl_context();
  const lucent::Scene scene = lucent::parse_scene(scene_json(method), "conformance scene", ".");
  const Rendered a = render(scene), b = render(scene);
  int object_pixels = 0;
  const double mean = mean_over_object(a.radiance, a.radiance, &object_pixels);
  EXPECT_GT(object_pixels, kSize * kSize / 8) << method.name;
  EXPECT_GT(mean, 1e-3) << method.name << ": the sphere is black";
  for (float v : a.radiance.pixels) ASSERT_TRUE(std::isfinite(v)) << method.name;
  EXPECT_EQ(a.radiance.pixels, b.radiance.pixels) << method.name << ": two renders with the same seed differ";
  // Passes and statistics: the method's come from its declarations (the renderer adds its own few).
  std::set<std::string> declared_passes = {"camera_gbuffer", "tonemap"}, declared_stats = {"translucent_pixels",
                                                                                           "coverage", "gpu_memory"};
  for (const auto& p : method.passes) declared_passes.insert(std::string(p.name));
  for (const auto& s : method.stats) declared_stats.insert(std::string(s.name));
  ASSERT_FALSE(a.last.passes.empty()) << method.name;
  for (const lucent::PassTiming& p : a.last.passes)
    EXPECT_TRUE(declared_passes.count(p.name)) << method.name << " ran an undeclared pass " << p.name;
  for (const lucent::FrameStatistic& s : a.last.stats)
    EXPECT_TRUE(declared_stats.count(s.name)) << method.name << " reported an undeclared statistic " << s.name;
  for (const auto& s : method.stats)
    EXPECT_GE(a.last.stat(std::string(s.name), -1.0), 0.0) << method.name << " did not report " << s.name;
  EXPECT_EQ(a.last.frame, 2u);
  EXPECT_NEAR(a.last.stat("translucent_pixels"), object_pixels, 0.0) << method.name;
}

TEST_P(MethodConformance, ABadParameterIsOneClearError) {
  const lucent::methods::MethodInfo& method = *GetParam();
  for (const lucent::ParamDecl& p : method.params) {
    if (p.type != lucent::ParamType::Int && p.type != lucent::ParamType::Float) continue;
    const std::string json = scene_json(method, fmt::format(R"("{}": {})", p.name, p.max * 2 + 1));
    std::string message;
    try {
      lucent::parse_scene(json, "conformance scene", ".");
    } catch (const lucent::Error& e) {
      message = e.what();
    }
    EXPECT_NE(message.find(fmt::format("conformance scene: /method/{}: ", p.name)), std::string::npos)
        << method.name << "." << p.name << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST_P(MethodConformance, AgreesWithTheBssrdfReferenceWithinItsTolerance) {
  const lucent::methods::MethodInfo& method = *GetParam();
  lucent::test::ensure_gl_context();
  lucent::Scene scene = lucent::parse_scene(scene_json(method), "conformance scene", ".");
  scene.render.frames = 8;  // progressive methods: a less noisy mean
  const Rendered rendered = render(scene);
  lucent::reference::ReferenceSettings settings;
  settings.integrator = lucent::reference::Integrator::Bssrdf;
  settings.samples_per_pixel = 16;
  const lucent::reference::ReferenceImage reference = lucent::reference::render_reference(scene, settings);
  const double ours = mean_over_object(rendered.radiance, rendered.radiance);
  const double theirs = mean_over_object(reference.mean, rendered.radiance);
  const double relative = std::fabs(ours - theirs) / theirs;
  fmt::print("{}: mean radiance over the sphere {:.5f}, bssrdf reference {:.5f}, relative error {:.3f} "
             "(declared tolerance {:.2f})\n",
             method.name, ours, theirs, relative, method.reference_tolerance);
  EXPECT_LE(relative, method.reference_tolerance) << method.name;
}

// The scenes where methods are weakest: the method's quick_settings, the sphere's material, 48 x 48 pixels.
enum class WeakScene { Sphere, BacklitSlab, CoarseBox };
constexpr WeakScene kWeakScenes[] = {WeakScene::Sphere, WeakScene::BacklitSlab, WeakScene::CoarseBox};

const char* weak_scene_name(WeakScene s) {
  return s == WeakScene::Sphere ? "sphere" : s == WeakScene::BacklitSlab ? "backlit_slab" : "coarse_box";
}

std::string weak_scene_json(const lucent::methods::MethodInfo& method, WeakScene which) {
  std::string json = scene_json(method);
  if (which == WeakScene::Sphere) return json;
  // A slab 0.5 mm thick (about 1.2 transport mean free paths) filling the view, lit from behind: only light that
  // crossed it reaches the camera. A box of eight vertices, 1.6 mm on a side, three faces seen, lit obliquely.
  const std::string sphere = R"("shape": "sphere", "radius": 1, "segments": 64,)";
  const std::string shape = which == WeakScene::BacklitSlab
                                ? R"("shape": "box", "size": [4, 4, 0.5],)"
                                : R"("shape": "box", "size": [1.6, 1.6, 1.6], "rotate_deg": [25, 35, 0],)";
  json.replace(json.find(sphere), sphere.size(), shape);
  if (which == WeakScene::BacklitSlab) {
    const std::string light = R"("direction": [-0.8, -0.3, -0.5])";
    json.replace(json.find(light), light.size(), R"("direction": [0.25, -0.15, 0.95])");
  }
  return json;
}

struct WeakCase {
  const lucent::methods::MethodInfo* method;
  WeakScene scene;
};

class MethodWhereWeakest : public ::testing::TestWithParam<WeakCase> {};

// The reference of a weak scene, shared by the methods that compare against the same integrator: the scene differs
// between them only in its "method" block, which no reference reads. Kept in the temporary folder under a name
// that holds the test binary's build time, so a rebuilt binary (changed code) never reads an older one; the first
// test process to need it renders it (two at once both do, and write the same set whole).
lucent::reference::ReferenceImage shared_reference(const lucent::Scene& scene, WeakScene which,
                                                  const lucent::reference::ReferenceSettings& settings) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto built = fs::last_write_time(fs::read_symlink("/proc/self/exe", ec), ec).time_since_epoch().count();
  const fs::path folder = fs::temp_directory_path() / "lucent_conformance_references";
  fs::create_directories(folder, ec);
  std::string name = fmt::format("{}_{}_{}_{}", weak_scene_name(which), to_string(settings.integrator),
                                 settings.samples_per_pixel, built);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  const lucent::reference::ReferenceFiles files = lucent::reference::reference_files((folder / (name + ".exr")).string());
  if (!ec && fs::exists(files.metadata)) {
    try {
      return lucent::reference::load_reference(files).image;
    } catch (const lucent::Error&) {  // being written by another test process: render it here
    }
  }
  lucent::reference::ReferenceImage image = lucent::reference::render_reference(scene, settings);
  if (!ec) lucent::reference::save_reference(files, image, nlohmann::json::object());
  return image;
}

// Relative error of the mean and noise-corrected relative RMS error per pixel over the object's pixels.
TEST_P(MethodWhereWeakest, AgreesWithItsReferencePerPixel) {
  const lucent::methods::MethodInfo& method = *GetParam().method;
  const WeakScene which = GetParam().scene;
  lucent::test::ensure_gl_context();
  lucent::Scene scene = lucent::parse_scene(weak_scene_json(method, which), "conformance scene", ".");
  scene.render.frames = 8;
  const Rendered rendered = render(scene);
  lucent::reference::ReferenceSettings settings;
  settings.integrator =
      method.estimates_volpath ? lucent::reference::Integrator::Volpath : lucent::reference::Integrator::Bssrdf;
  settings.samples_per_pixel = method.estimates_volpath ? 64 : 4096;
  const lucent::reference::ReferenceImage reference = shared_reference(scene, which, settings);
  double sum_a = 0.0, sum_b = 0.0, squared = 0.0, noise = 0.0;
  int n = 0;
  const std::vector<float>& a = rendered.radiance.pixels;
  for (std::size_t i = 0; i < a.size(); i += 4) {
    if (a[i + 3] <= 0.5f) continue;
    for (int c = 0; c < 3; ++c) {
      const double ours = a[i + c], theirs = reference.mean.pixels[i + c], se = reference.standard_error.pixels[i + c];
      sum_a += ours;
      sum_b += theirs;
      squared += (ours - theirs) * (ours - theirs);
      noise += se * se;
    }
    ++n;
  }
  ASSERT_GT(n, kSize * kSize / 8) << method.name;
  ASSERT_GT(sum_b, 0.0) << method.name;
  const double mean_b = sum_b / (3.0 * n);
  const double mean_error = std::fabs(sum_a - sum_b) / sum_b;
  const double pixel_error = std::sqrt(std::max(0.0, squared - noise) / (3.0 * n)) / mean_b;
  const lucent::methods::ConformanceTolerances& t = method.weakest;
  const double mean_tolerance = which == WeakScene::Sphere        ? method.reference_tolerance
                                : which == WeakScene::BacklitSlab ? t.slab_mean
                                                                  : t.box_mean;
  const double pixel_tolerance = which == WeakScene::Sphere        ? t.sphere_pixels
                                 : which == WeakScene::BacklitSlab ? t.slab_pixels
                                                                   : t.box_pixels;
  fmt::print("{} on the {}: mean {:.5f} against {:.5f} ({} reference), relative error of the mean {:.3f} (declared "
             "{:.2f}), per pixel {:.3f} (declared {:.2f})\n",
             method.name, weak_scene_name(which), sum_a / (3.0 * n), mean_b,
             method.estimates_volpath ? "volpath" : "bssrdf", mean_error, mean_tolerance, pixel_error, pixel_tolerance);
  EXPECT_LE(mean_error, mean_tolerance) << method.name << " on the " << weak_scene_name(which);
  EXPECT_LE(pixel_error, pixel_tolerance) << method.name << " on the " << weak_scene_name(which);
}

std::vector<WeakCase> weak_cases() {
  std::vector<WeakCase> cases;
  for (const lucent::methods::MethodInfo* method : lucent::methods::method_registry())
    for (WeakScene s : kWeakScenes) cases.push_back({method, s});
  return cases;
}

std::string weak_case_name(const ::testing::TestParamInfo<WeakCase>& info) {
  std::string name = std::string(info.param.method->name) + "_" + weak_scene_name(info.param.scene);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MethodWhereWeakest, ::testing::ValuesIn(weak_cases()), weak_case_name);

std::string method_test_name(const ::testing::TestParamInfo<const lucent::methods::MethodInfo*>& info) {
  std::string name(info.param->name);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MethodConformance, ::testing::ValuesIn(lucent::methods::method_registry()),
                         method_test_name);

}  // namespace
