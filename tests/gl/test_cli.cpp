// test_cli.cpp: the `lucent` tool from outside: bad input gives one clear line and a non-zero exit; bssrdf
// prints the model's values; render writes a non-black image; help is generated from the declarations.
#include <array>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>
#include <sys/wait.h>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli_runner.h"
#include "image_compare.h"
#include "lucent/image.h"
#include "methods/method_info.h"
#include "platform/gl_capabilities.h"
#include "../test_paths.h"

namespace {

using Result = lucent::test::CliResult;

Result run(const std::string& arguments, const std::string& environment = "") {
  return lucent::test::run_cli(arguments, environment);
}

std::string write_file(const std::string& name, const std::string& text) {
  std::string path = lucent::test::output_path(name);
  std::ofstream(path) << text;
  return path;
}

const char* kSmall = "--set render.width=48 --set render.height=32 --set method.K=4 --set method.N=4 "
                     "--set method.map_size=32 --set method.light_map_size=64";

void expect_one_line_error(const Result& r, const std::string& expected_line) {
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.output, expected_line + "\n");
}

TEST(Cli, MissingMeshFile) {
  std::string scene = write_file("missing_mesh.json", R"({"objects": [{"mesh": "no_such_mesh.obj", "material": "Marble"}]})");
  std::string mesh = lucent::test::output_path("no_such_mesh.obj");
  expect_one_line_error(run("render " + scene),
                        "lucent: " + scene + ": /objects/0/mesh: " + mesh + ": no such file");
}

TEST(Cli, BenchRunsMustBeAnArray) {
  std::string config = write_file("bench_runs_object.json", R"({"runs": {"name": "marble"}})");
  expect_one_line_error(run("bench " + config + " -o " + lucent::test::output_path("bench_runs_object")),
                        "lucent: " + config + ": \"runs\" must be an array of runs");
}

// The bench from outside, on a tiny matrix: --run runs one run of the configuration; its error equals the RMSE
// computed here from the files it wrote (the method's EXR and the cached reference); the reference was refined
// until its noise is noise_ratio times below the noise-corrected RMSE (or max_spp); a second bench reuses the
// cached reference instead of rendering it again; an unknown run name is one clear error.
TEST(Cli, BenchRunsOneRunAndRefinesItsReferenceToTheNoiseRatio) {
  namespace fs = std::filesystem;
  const fs::path dir = lucent::test::output_path("bench_one_run");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = (dir / "sphere.json").string(), config = (dir / "bench.json").string();
  std::ofstream(scene) << R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]},
    "lights": [{"direction": [0.5, 0, -1]}], "objects": [{"shape": "sphere", "material": "Skin1"}]})";
  constexpr double kRatio = 3.0;
  constexpr int kFirstSpp = 4, kMaxSpp = 4096;
  nlohmann::json bench = {
      {"set", {"render.width=24", "render.height=16", "method.K=4", "method.N=4", "method.map_size=32",
               "method.light_map_size=64", "method.specular=false", "render.background=[0,0,0]"}},
      {"references",
       {{"bssrdf", {{"spp", kFirstSpp}, {"noise_ratio", kRatio}, {"max_spp", kMaxSpp}, {"rmse_floor", 1e-4}}}}},
      {"runs",
       {{{"name", "skin"}, {"scene", scene}, {"variants", {{{"name", "one"}, {"id", "one"}, {"frames", 1}}}}},
        {{"name", "marble"},
         {"scene", scene},
         {"set", {R"(objects.0.material={"preset": "Marble"})"}},
         {"variants", {{{"name", "four frames"}, {"id", "four"}, {"frames", 4}}}}}}}};
  std::ofstream(config) << bench.dump(2);
  const std::string out = (dir / "out").string();

  Result first = run("bench " + config + " --run marble -o " + out);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  auto results = nlohmann::json::parse(std::ifstream(fs::path(out) / "results.json"));
  EXPECT_EQ(results["only_runs"], nlohmann::json::array({"marble"}));
  EXPECT_TRUE(results["complete"].get<bool>());
  ASSERT_EQ(results["results"].size(), 1u);
  const nlohmann::json& error = results["results"][0]["error"]["bssrdf"];

  // Only the marble run's reference was rendered: one metadata file in the cache.
  std::vector<fs::path> metadata;
  for (const auto& entry : fs::directory_iterator(fs::path(out) / "references"))
    if (entry.path().filename().string().ends_with(".meta.json")) metadata.push_back(entry.path());
  ASSERT_EQ(metadata.size(), 1u);
  auto meta = nlohmann::json::parse(std::ifstream(metadata[0]));
  const int spp = meta["samples_per_pixel"].get<int>();
  EXPECT_EQ(spp, error["reference_spp"].get<int>());
  EXPECT_GT(spp, kFirstSpp) << "the first reference already met the ratio: the test no longer checks refinement";

  // RMSE of sqrt(dr^2+dg^2+db^2) and the reference's noise, from the written files.
  fs::path ref_exr = metadata[0];
  ref_exr.replace_extension("").replace_extension(".exr");  // <key>.meta.json -> <key>.exr
  fs::path ref_stderr = ref_exr;
  ref_stderr.replace_extension(".stderr.exr");
  const lucent::ImageRGBA32F method = lucent::read_exr((fs::path(out) / "images" / "marble+four.exr").string());
  const lucent::ImageRGBA32F reference = lucent::read_exr(ref_exr.string());
  const lucent::ImageRGBA32F standard_error = lucent::read_exr(ref_stderr.string());
  ASSERT_EQ(method.pixels.size(), reference.pixels.size());
  double squared = 0.0, variance = 0.0;
  const std::size_t n = method.pixels.size() / 4;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c) {
      double d = double(method.pixels[4 * i + c]) - reference.pixels[4 * i + c];
      squared += d * d;
      variance += double(standard_error.pixels[4 * i + c]) * standard_error.pixels[4 * i + c];
    }
  const double rmse = std::sqrt(squared / double(n)), noise = std::sqrt(variance / double(n));
  EXPECT_NEAR(error["rmse_rgb"].get<double>(), rmse, 1e-9 * rmse);
  EXPECT_GT(rmse, 1e-3) << "a black image or reference would meet any ratio";
  const double corrected = std::sqrt(std::max(0.0, rmse * rmse - noise * noise));
  EXPECT_TRUE(noise * kRatio <= std::max(corrected, 1e-4) || spp >= kMaxSpp)
      << "noise " << noise << " x " << kRatio << " > corrected RMSE " << corrected << " at " << spp << " spp";

  // A second bench finds the reference in the cache: not rendered again (same metadata), same error.
  Result second = run("bench " + config + " --run marble -o " + out);
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(metadata[0])), meta);
  auto again = nlohmann::json::parse(std::ifstream(fs::path(out) / "results.json"));
  EXPECT_EQ(again["results"][0]["error"]["bssrdf"]["rmse_rgb"], error["rmse_rgb"]);

  expect_one_line_error(run("bench --run marbel " + config + " -o " + out),  // one name per --run
                        "lucent: " + config + ": --run marbel: no such run; runs: skin, marble");
}

// A matrix of every method over every scene (the leaderboard's shape): the configuration's "variants" serve every
// run without its own; with "record_refusals" a method that refuses a scene (local-global on a deforming object) is
// recorded with its one-line message and the bench goes on; `--set` overrides come last, after the variant's own.
TEST(Cli, BenchSharesVariantsRecordsRefusalsAndTakesOverrides) {
  namespace fs = std::filesystem;
  const fs::path dir = lucent::test::output_path("bench_refusals");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string still = (dir / "still.json").string(), bending = (dir / "bending.json").string();
  const std::string config = (dir / "bench.json").string();
  std::ofstream(still) << R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]},
    "lights": [{"direction": [0.5, 0, -1]}], "objects": [{"shape": "sphere", "material": "Skin1"}]})";
  std::ofstream(bending) << R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]},
    "lights": [{"direction": [0.5, 0, -1]}], "objects": [{"name": "ball", "shape": "sphere", "material": "Skin1",
    "deform": {"type": "bend", "start_s": 1}}]})";
  nlohmann::json bench = {
      {"record_refusals", true},
      {"set", {"render.width=16", "render.height=12", "render.background=[0,0,0]"}},
      {"variants",
       {{{"name", "wrap"}, {"id", "wrap"}, {"set", {R"(method={"name": "diffuse-wrap", "wrap": 0.5})"}}},
        {{"name", "lg"}, {"id", "lg"}, {"set", {R"(method={"name": "local-global", "atlas_size": 64})"}}}}},
      {"runs", {{{"name", "still"}, {"scene", still}}, {{"name", "bending"}, {"scene", bending}}}}};
  std::ofstream(config) << bench.dump(2);
  const std::string out = (dir / "out").string();
  Result r = run("bench " + config + " -o " + out + " --set method.specular=false");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto doc = nlohmann::json::parse(std::ifstream(fs::path(out) / "results.json"));
  EXPECT_EQ(doc["set"], nlohmann::json::array({"method.specular=false"}));
  ASSERT_EQ(doc["results"].size(), 4u);
  std::map<std::string, nlohmann::json> by;
  for (const auto& result : doc["results"])
    by[result["run"].get<std::string>() + "/" + result["variant"].get<std::string>()] = result;
  ASSERT_EQ(by.size(), 4u);
  for (const char* key : {"still/wrap", "still/lg", "bending/wrap"}) {
    EXPECT_FALSE(by[key].contains("refused")) << key << ": " << by[key].dump();
    EXPECT_EQ(by[key]["params"]["specular"], false) << key << ": --set applies to every variant";
  }
  EXPECT_EQ(by["still/wrap"]["params"]["wrap"], 0.5);
  EXPECT_EQ(by["bending/lg"]["method"], "local-global");
  EXPECT_EQ(by["bending/lg"]["refused"],
            bending + ": object 'ball': local-global precomputes transport over a fixed mesh; deforming objects are "
                      "not supported (rigid objects only)");
  std::ostringstream md_text;
  md_text << std::ifstream(fs::path(out) / "results.md").rdbuf();
  const std::string md = md_text.str();
  EXPECT_NE(md.find("| bending | lg | local-global | refused: "), std::string::npos) << md;
}

// Image names are unique across runs: run x with variant y_f1 and run x_y with variant f1 both wrote x_y_f1.png, and
// runs a.b and a_b one file each; results.json pointed two results at one image. Each run has its own background
// colour, so an image shows which run wrote it.
TEST(Cli, BenchImageNamesNeverCollide) {
  namespace fs = std::filesystem;
  const fs::path dir = lucent::test::output_path("bench_names");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = (dir / "s.json").string(), config = (dir / "bench.json").string();
  std::ofstream(scene) << R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]}, "lights": [{"direction": [0.5, 0, -1]}],
    "objects": [{"name": "ball", "shape": "sphere", "radius": 0.5, "material": "Skin1"}],
    "method": {"name": "diffuse-wrap"}, "render": {"width": 16, "height": 12, "tonemap": "linear"}})";
  const std::vector<std::pair<std::string, std::string>> runs = {{"x", "y_f1"}, {"x_y", "f1"}, {"a.b", "v"}, {"a_b", "v"}};
  nlohmann::json bench = {{"references", {{"bssrdf", {{"spp", 1}}}}}, {"runs", nlohmann::json::array()}};
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string background = fmt::format("render.background=[{}, {}, {}]", int(i == 0), int(i == 1), int(i == 2));
    bench["runs"].push_back({{"name", runs[i].first},
                             {"scene", scene},
                             {"set", {background}},
                             {"regions", {{{"name", "ball"}, {"object", "ball"}}}},
                             {"variants", {{{"name", runs[i].second}, {"frames", 1}}}}});
  }
  std::ofstream(config) << bench.dump(2);
  const fs::path out = dir / "out";
  Result r = run("bench " + config + " -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto doc = nlohmann::json::parse(std::ifstream(out / "results.json"));
  ASSERT_EQ(doc["results"].size(), runs.size());
  std::set<std::string> images;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const nlohmann::json& result = doc["results"][i];
    ASSERT_EQ(result["run"], runs[i].first);
    for (const std::string& image : {result["image"].get<std::string>(),
                                    result["error"]["bssrdf"]["reference_image"].get<std::string>()}) {
      EXPECT_TRUE(images.insert(image).second) << image << " is named by two results";
      // The corner shows the run's background: red, green, blue, black.
      const lucent::ImageRGBA8 png = lucent::read_png((out / image).string());
      const std::uint8_t* corner = png.at(0, 0);
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(corner[c] > 128, static_cast<std::size_t>(c) == i) << image << " channel " << c;
    }
  }
  EXPECT_EQ(images.count("images/x+y_f1.png") + images.count("images/x_y+f1.png") + images.count("images/a.b+v.png") +
                images.count("images/a_b+v.png"),
            4u);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(out / "images")) files += entry.is_regular_file();
  // Per run: the variant's PNG and EXR, its heat map, the reference and the region: 5 files, none shared.
  EXPECT_EQ(files, 5 * runs.size());
}

TEST(Cli, MalformedJson) {
  std::string scene = write_file("malformed.json", R"({"objects": [ )");
  Result r = run("render " + scene);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.output.rfind("lucent: " + scene + ": malformed JSON:", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1);
}

TEST(Cli, UnknownKey) {
  std::string scene = write_file("unknown_key.json", R"({"objects": [{"shape": "sphere", "colour": [1, 0, 0]}]})");
  expect_one_line_error(
      run("render " + scene),
      "lucent: " + scene + ": /objects/0/colour: unknown key; known keys: name, shape, mesh, radius, inner_radius, "
      "major_radius, minor_radius, size, extent, segments, translate, rotate_deg, scale, up_axis, albedo, material, profile, deform");
}

TEST(Cli, NegativeSigma) {
  std::string scene = write_file("negative_sigma.json", R"({"objects": [{"shape": "sphere",
    "material": {"sigma_a": [0.01, -0.1, 0.01], "sigma_s_prime": [1, 1, 1]}}]})");
  expect_one_line_error(run("render " + scene), "lucent: " + scene +
                                                    ": /objects/0/material: sigma_a[1] = -0.1 is negative; allowed "
                                                    "range [0, inf) mm^-1");
}

TEST(Cli, ZeroMapSize) {
  expect_one_line_error(run("render --set method.map_size=0"),
                        "lucent: --set 'method.map_size=0': /method/map_size: 0 is out of range; allowed range "
                        "[8, 4096] texels");
}

TEST(Cli, NoGlContext) {
  // An EGL vendor list with no vendor: glvnd finds no driver, as on a machine without Mesa or a GPU driver.
  Result r = run(std::string("render ") + kSmall, "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.output.rfind("lucent: no OpenGL context: ", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST(Cli, DriverWithoutOpenGl45) {
  // Mesa's MESA_GL_VERSION_OVERRIDE makes the driver offer only OpenGL 4.3; other drivers ignore it.
  lucent::test::ensure_gl_context();
  if (lucent::platform::current_capabilities().renderer.find("llvmpipe") == std::string::npos)
    GTEST_SKIP() << "needs Mesa llvmpipe";
  expect_one_line_error(run(std::string("render ") + kSmall, "MESA_GL_VERSION_OVERRIDE=4.3"),
                        "lucent: no OpenGL context: the driver cannot create an OpenGL 4.5 core context (EGL error "
                        "0x3009)");
}

TEST(Cli, BssrdfPrintsPotatoReferenceValues) {
  Result r = run("bssrdf --model directional --material Potato --xi 0,0,0 --ni 0,0,1 --wi 0,0,1 --xo 1,0,0 "
                 "--no 0,0,1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto j = nlohmann::json::parse(r.output);
  const double expected[3] = {9.567225e-03, 9.536976e-03, 6.863451e-03};  // shared/spec/bssrdf-models.md 1.7
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(j["S_d"][c].get<double>(), expected[c], 2e-4 * expected[c]);
  EXPECT_NEAR(j["T12"].get<double>(), 0.982987, 1e-6);
}

TEST(Cli, BssrdfRejectsUnknownMaterial) {
  expect_one_line_error(run("bssrdf --material Unobtainium"),
                        "lucent: --material: unknown material 'Unobtainium' (see: lucent materials)");
}

TEST(Cli, RenderHelpListsDeclaredParameters) {
  Result r = run("render --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* text : {"eps_bias", "map texels", "light_map_size", "scale_mm", "fov_y_deg", "sigma_s_prime"})
    EXPECT_NE(r.output.find(text), std::string::npos) << text;
}

TEST(Cli, MaterialsListsPresets) {
  Result r = run("materials");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("Marble"), std::string::npos);
  EXPECT_NE(r.output.find("White Grapefruit Juice"), std::string::npos);
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 48);  // header + 47 presets
}

TEST(Cli, RenderWritesNonBlackImage) {
  std::string png = lucent::test::output_path("cli_default.png");
  Result r = run(std::string("render ") + kSmall + " --frames 2 -o " + png);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The summary lists the method's own passes (as it declares them) and its statistics.
  EXPECT_NE(r.output.find("  integrate "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("statistics (median): translucent_pixels "), std::string::npos) << r.output;
  lucent::ImageRGBA8 image = lucent::read_png(png);
  ASSERT_EQ(image.width, 48);
  double sum = 0.0;
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) sum += image.pixels[i];
  EXPECT_GT(sum / (48.0 * 32.0), 20.0);  // mean red above 20/255: lit objects, not black
}

// -o's extension picks the format: .exr writes the linear radiance (what --exr writes beside a PNG), .png the
// tone-mapped image; any other extension is one line naming the option, before anything renders.
TEST(Cli, RenderOutputFormatFollowsTheExtension) {
  const std::string exr = lucent::test::output_path("cli_output.exr"), png = lucent::test::output_path("cli_output.png");
  const std::string beside = lucent::test::output_path("cli_output_beside.exr");
  Result as_exr = run(std::string("render ") + kSmall + " --frames 1 -q -o " + exr);
  ASSERT_EQ(as_exr.exit_code, 0) << as_exr.output;
  Result as_png = run(std::string("render ") + kSmall + " --frames 1 -q -o " + png + " --exr " + beside);
  ASSERT_EQ(as_png.exit_code, 0) << as_png.output;
  const lucent::ImageRGBA32F radiance = lucent::read_exr(exr), other = lucent::read_exr(beside);
  ASSERT_EQ(radiance.width, 48);
  ASSERT_EQ(radiance.height, 32);
  ASSERT_EQ(radiance.pixels.size(), other.pixels.size());
  double peak = 0.0, largest_difference = 0.0;
  for (std::size_t i = 0; i < radiance.pixels.size(); ++i) {
    peak = std::max(peak, static_cast<double>(radiance.pixels[i]));
    largest_difference = std::max(largest_difference, std::abs(static_cast<double>(radiance.pixels[i]) - other.pixels[i]));
  }
  EXPECT_GT(peak, 0.0);
  EXPECT_LE(largest_difference, 1e-3 * peak);
  EXPECT_EQ(lucent::read_png(png).width, 48);
  const std::string tif = lucent::test::output_path("cli_output.tif");
  Result bad = run(std::string("render ") + kSmall + " --frames 1 -q -o " + tif);
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_EQ(bad.output, "lucent: --output " + tif + ": '.tif' is not a format this command writes; use .png or .exr\n");
}

// --timings-json: one entry per frame rendered, in order, with the passes the method declares (and the
// renderer's own) and its statistics.
TEST(Cli, RenderTimingsJsonHasEveryFrameWithDeclaredPassesAndStatistics) {
  std::string json_path = lucent::test::output_path("cli_timings.json");
  std::string png = lucent::test::output_path("cli_timings.png");
  Result r = run(std::string("render ") + kSmall + " --frames 3 -q -o " + png + " --timings-json " + json_path);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(json_path);
  nlohmann::json timings = nlohmann::json::parse(in);
  ASSERT_EQ(timings["frames"].size(), 3u);
  for (int f = 0; f < 3; ++f) {
    const nlohmann::json& frame = timings["frames"][static_cast<std::size_t>(f)];
    EXPECT_EQ(frame["frame"].get<int>(), f + 1);
    double sum = 0.0;
    for (const auto& [name, ms] : frame["passes"].items()) sum += ms.get<double>();
    EXPECT_NEAR(frame["total_ms"].get<double>(), sum, 1e-6 * sum + 1e-9);
    for (const char* pass : {"camera_gbuffer", "light_gbuffer", "map_gbuffers", "integrate", "combine", "tonemap"})
      EXPECT_TRUE(frame["passes"].contains(pass)) << pass;
    EXPECT_GT(frame["stats"]["translucent_pixels"].get<double>(), 0.0);
    EXPECT_GT(frame["stats"]["bssrdf_samples"].get<double>(), 0.0);
  }
}

// --restart-every-frame: every frame recomputes what the method caches (radiosity-maps stops recomputing its maps
// once converged; with the flag it never converges) and the image is the last frame alone; it cannot be combined
// with --animate.
TEST(Cli, RenderRestartEveryFrameRecomputesCachedState) {
  std::string png = lucent::test::output_path("cli_restart.png");
  auto converged_per_frame = [&](const std::string& extra) {
    std::string json_path = lucent::test::output_path("cli_restart.json");
    Result r = run(std::string("render ") + kSmall + " --set method.converged_after=1 --frames 3 -o " + png +
                   " --timings-json " + json_path + extra);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    std::ifstream in(json_path);
    nlohmann::json timings = nlohmann::json::parse(in);
    std::vector<double> converged;
    for (const nlohmann::json& frame : timings["frames"]) converged.push_back(frame["stats"]["converged"].get<double>());
    return std::make_pair(converged, r.output);
  };
  auto [cached, cached_output] = converged_per_frame("");
  (void)cached_output;
  EXPECT_EQ(cached, (std::vector<double>{0, 1, 1}));
  auto [restarted, restarted_output] = converged_per_frame(" --restart-every-frame");
  EXPECT_EQ(restarted, (std::vector<double>{0, 0, 0}));
  EXPECT_NE(restarted_output.find(", 1 frame(s) accumulated"), std::string::npos) << restarted_output;
  expect_one_line_error(run("render --restart-every-frame --animate -q -o " + png),
                        "lucent: --animate excludes --restart-every-frame (lucent --help lists the options)");
}

// `lucent methods --json`: every registered method, with typed parameters marked live or rebuild, its passes and
// statistics; the text form names the default.
TEST(Cli, MethodsListsEveryMethodWithParametersPassesAndStatistics) {
  Result r = run("methods --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  nlohmann::json methods = nlohmann::json::parse(r.output);
  std::vector<std::string> names;
  for (const nlohmann::json& m : methods) {
    names.push_back(m["name"]);
    EXPECT_FALSE(m["passes"].empty()) << m["name"];
    for (const nlohmann::json& p : m["params"]) {
      EXPECT_TRUE(p["update"] == "live" || p["update"] == "rebuild") << p.dump();
      EXPECT_TRUE(p.contains("type") && p.contains("default") && p.contains("unit")) << p.dump();
    }
  }
  std::vector<std::string> registered;  // the registry's order, the default first
  for (const lucent::methods::MethodInfo* m : lucent::methods::method_registry()) registered.emplace_back(m->name);
  EXPECT_EQ(names, registered);
  EXPECT_EQ(registered.front(), "radiosity-maps");
  const nlohmann::json& maps = methods[0];
  auto param = [&](const char* name) {
    for (const nlohmann::json& p : maps["params"])
      if (p["name"] == name) return p;
    return nlohmann::json();
  };
  EXPECT_EQ(param("N")["update"], "live");
  EXPECT_EQ(param("map_size")["update"], "rebuild");
  EXPECT_EQ(param("map_size")["min"].get<double>(), 8.0);
  EXPECT_EQ(param("view")["choices"], (nlohmann::json{"shaded", "coverage"}));
  Result text = run("methods");
  EXPECT_NE(text.output.find("radiosity-maps (default)"), std::string::npos) << text.output;
}

TEST(Cli, AnimateWritesNumberedFramesAndCallsFfmpeg) {
  // A stand-in ffmpeg on the PATH records how it is called (the real one is optional and not installed in CI).
  std::string dir = lucent::test::output_path("animate");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/bin");
  std::string fake = dir + "/bin/ffmpeg";
  // It writes its last argument (the output), as ffmpeg does, from the frames ffmpeg's image2 input would read: the
  // pattern's files from number 0 on while they exist, at most -frames:v of them.
  std::ofstream(fake) << "#!/bin/sh\necho \"$@\" > " << dir << "/ffmpeg_args.txt\n"
                      << "n=-1\nwhile [ $# -gt 1 ]; do\n"
                      << "  case $1 in -frames:v) n=$2;; -i) pattern=$2;; esac; shift\ndone\n"
                      << "count=0\nwhile [ $n -lt 0 ] || [ $count -lt $n ]; do\n"
                      << "  [ -f \"$(printf \"$pattern\" $count)\" ] || break; count=$((count + 1))\ndone\n"
                      << "echo video of $count frames > \"$1\"\n";
  std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
  // A frame of an earlier, longer animation is no part of this one's video.
  std::ofstream(dir + "/blobs_0002.png") << "an earlier animation's frame";
  std::string scene = std::string(LUCENT_SCENES_DIR) + "/blobs.json";
  Result r = run("render " + scene + " " + kSmall + " --set method.vpls=0 --set objects.0.segments=24 --animate --frames 2 -o " +
                     dir + "/blobs.png",
                 "PATH=" + dir + "/bin:$PATH");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  lucent::ImageRGBA8 a = lucent::read_png(dir + "/blobs_0000.png"), b = lucent::read_png(dir + "/blobs_0001.png");
  EXPECT_NE(a.pixels, b.pixels) << "the blobs move between frames";
  std::ifstream args_file(dir + "/ffmpeg_args.txt");
  std::string args((std::istreambuf_iterator<char>(args_file)), std::istreambuf_iterator<char>());
  EXPECT_NE(args.find("-framerate 30 -i " + dir + "/blobs_%04d.png -frames:v 2 "), std::string::npos) << args;
  // ffmpeg reads commands from its standard input unless told not to: it would take a pipe's lines meant for
  // others, or stop a background job (SIGTTIN) that shares the terminal.
  EXPECT_EQ(args.rfind("-nostdin ", 0), 0u) << args;
  // ffmpeg writes a temporary beside the video, renamed into place when it succeeded.
  EXPECT_NE(args.find(dir + "/.blobs.lucent-tmp.mp4"), std::string::npos) << args;
  std::ifstream video(dir + "/blobs.mp4");
  std::string first_line;
  std::getline(video, first_line);
  EXPECT_EQ(first_line, "video of 2 frames");
  EXPECT_FALSE(std::filesystem::exists(dir + "/.blobs.lucent-tmp.mp4"));
}

TEST(Cli, RenderWriteErrorsAreErrors) {
  expect_one_line_error(run(std::string("render ") + kSmall + " -q -o /dev/full"),
                        "lucent: /dev/full: cannot write: No space left on device");
}

// Maps larger than the device's memory are refused before any allocation, naming the parameters (the driver's own
// answer was "framebuffer incomplete (status 0x8cd6)", or on llvmpipe the out-of-memory killer).
TEST(Cli, MapsLargerThanTheDeviceAreRefusedNamingTheParameters) {
  lucent::test::ensure_gl_context();
  const auto& caps = lucent::platform::current_capabilities();
  const double needed_gib = 4096.0 * 4096.0 * 64.0 * (28.0 + 64.0 / 3.0) / (1024.0 * 1024.0 * 1024.0);
  if (caps.device_memory_bytes == 0 || static_cast<double>(caps.device_memory_bytes) >= needed_gib * 1073741824.0)
    GTEST_SKIP() << "the device has room for the maps (or does not report its memory)";
  Result r = run("render -q --set method.map_size=4096 --set method.K=64 -o " + lucent::test::output_path("huge.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output.rfind("lucent: method.map_size 4096, method.K 64, method.light_map_size 512, method.vpl_map_size "
                           "256: the scattered-radiosity maps and their G-buffer: 49.3 GiB of GPU memory needed; the "
                           "device (",
                           0),
            0u)
      << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

}  // namespace
