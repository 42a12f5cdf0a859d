// test_method_conformance.cpp: what every registered method must do, checked over the registry (a new method is
// tested by registering it): on a small scene (a sphere of skim-milk-like material lit from the side, with the
// method's quick_settings) the output is finite and not blank, the same for the same seed, its passes and
// statistics are the ones it declares, a bad parameter value is one clear error naming the parameter, and the mean
// radiance over the sphere agrees with the CPU bssrdf reference within the tolerance the method declares.
#include <cmath>
#include <set>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "image_compare.h"
#include "lucent/lucent.h"
#include "methods/method_info.h"
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

std::string method_test_name(const ::testing::TestParamInfo<const lucent::methods::MethodInfo*>& info) {
  std::string name(info.param->name);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MethodConformance, ::testing::ValuesIn(lucent::methods::method_registry()),
                         method_test_name);

}  // namespace
