// test_cli_references.cpp: `lucent slab`, `lucent reference` and `lucent compare` from outside: exact errors for
// bad input, the files a reference run writes, and compare's numbers on an image against itself.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <sys/wait.h>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "reference/reference_cache.h"
#include "../cli_runner.h"
#include "lucent/image.h"
#include <nlohmann/json.hpp>

namespace {

using Result = lucent::test::CliResult;

Result run(const std::string& arguments) { return lucent::test::run_cli(arguments); }

std::filesystem::path references_dir() {
  auto dir = std::filesystem::temp_directory_path() / "lucent_cli_references";
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(CliReferences, SlabRejectsBadAlbedoAndPrintsJson) {
  Result bad = run("slab --albedo 1.5");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_EQ(bad.output, "lucent: --albedo 1.5 is out of range; allowed range [0, 1]\n");
  Result ok = run("slab --albedo 0.9 --photons 20000 --json");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  auto j = nlohmann::json::parse(ok.output);
  EXPECT_NEAR(j["diffuse_reflectance"]["mean"].get<double>(), 0.414948,
              4.0 * j["diffuse_reflectance"]["standard_error"].get<double>());
}

// `lucent bssrdf --total`: the model's flat half-space total per refracted power, per channel under "total": for
// the standard dipole with its exit normalisation, Jensen's closed-form R_total (within the 2e-3 of the Fresnel
// moment's polynomial fit); --incidence-deg only with --total.
TEST(CliReferences, BssrdfTotalPrintsTheModelsFlatReflectance) {
  Result ok = run("bssrdf --total --model standard --sigma-a 0.01,0.01,0.01 --sigma-s-prime 0.99,0.99,0.99 --eta 1.3 --json");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  auto j = nlohmann::json::parse(ok.output);
  const double a = 0.99, A = (1.0 + 0.444763) / (1.0 - 0.444763), s = std::sqrt(3.0 * (1.0 - a));
  const double r_total = 0.5 * a * (1.0 + std::exp(-4.0 / 3.0 * A * s)) * std::exp(-s);
  ASSERT_EQ(j["total"].size(), 3u);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(j["total"][c].get<double>(), r_total, 2e-3 * r_total);
  EXPECT_NEAR(j["exit_transmittance"].get<double>(), 4.0 * 0.234717, 2e-5);  // the spec's exact moment
  Result bad = run("bssrdf --incidence-deg 45 --material Marble");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_EQ(bad.output, "lucent: --incidence-deg requires --total (lucent --help lists the options)\n");
}

TEST(CliReferences, ReferenceWritesMeanErrorAndMetadataAndResumes) {
  auto dir = references_dir();
  std::string scene = (dir / "sphere.json").string(), exr = (dir / "ref.exr").string();
  std::ofstream(scene) << R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]},
    "lights": [{"direction": [0, 0, -1]}], "objects": [{"shape": "sphere", "material": "Skin1"}],
    "render": {"width": 12, "height": 8}})";
  Result first = run("reference " + scene + " --integrator bssrdf --spp 2 -q -o " + exr);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  Result second = run("reference " + scene + " --integrator bssrdf --spp 3 -q --resume -o " + exr);
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "ref.stderr.exr"));
  auto meta = nlohmann::json::parse(std::ifstream(dir / "ref.meta.json"));
  EXPECT_EQ(meta["samples_per_pixel"].get<int>(), 5);
  Result self = run("compare " + exr + " " + exr + " --json");
  ASSERT_EQ(self.exit_code, 0) << self.output;
  EXPECT_EQ(nlohmann::json::parse(self.output)["linear"]["rmse_rgb"].get<double>(), 0.0);
}

// --resume makes the checks merge makes: a reference whose mean or standard error is not finite and >= 0 anywhere
// (a NaN standard error resumed as 0 everywhere; a NaN or negative mean was carried on), one of another scene or
// one from another version of the estimators is refused, naming the file, and left as it was.
TEST(CliReferences, ResumeRefusesAnythingButTheSameReference) {
  auto dir = references_dir();
  const std::string scene = (dir / "resume_sphere.json").string(), exr = (dir / "resume.exr").string(),
                    stderr_exr = (dir / "resume.stderr.exr").string(), meta = (dir / "resume.meta.json").string();
  const std::string text = R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]},
    "lights": [{"direction": [0, 0, -1]}], "objects": [{"shape": "sphere", "material": "Skin1"}],
    "render": {"width": 12, "height": 8}})";
  std::ofstream(scene) << text;
  const std::string render = "reference " + scene + " --integrator bssrdf --spp 2 -q -o " + exr;
  const std::string resume = "reference " + scene + " --integrator bssrdf --spp 2 -q --resume -o " + exr;
  auto damaged = [&](const std::string& file, std::size_t index, float value) {
    EXPECT_EQ(run(render).exit_code, 0);
    lucent::ImageRGBA32F image = lucent::read_exr(file);
    image.pixels[index] = value;
    lucent::write_exr(file, image);
    return run(resume);
  };
  const std::size_t green_of_1_0 = 4 * 1 + 1;
  Result nan_se = damaged(stderr_exr, green_of_1_0, std::nanf(""));
  EXPECT_NE(nan_se.exit_code, 0);
  const float mean = lucent::read_exr(exr).pixels[green_of_1_0];
  EXPECT_EQ(nan_se.output, fmt::format("lucent: {}: pixel (1, 0) g has mean {} and standard error nan; a reference's "
                                       "are finite and >= 0 (see {})\n",
                                       exr, mean, stderr_exr));
  Result negative = damaged(exr, green_of_1_0, -0.25f);
  EXPECT_NE(negative.exit_code, 0);
  EXPECT_NE(negative.output.find("pixel (1, 0) g has mean -0.25 and standard error"), std::string::npos)
      << negative.output;
  Result nan_mean = damaged(exr, 0, std::nanf(""));
  EXPECT_NE(nan_mean.output.find("pixel (0, 0) r has mean nan"), std::string::npos) << nan_mean.output;
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(meta))["samples_per_pixel"].get<int>(), 2);  // left as it was

  // Version 1 (no "reference_version"): its samples estimate another image.
  ASSERT_EQ(run(render).exit_code, 0);
  nlohmann::json m = nlohmann::json::parse(std::ifstream(meta));
  EXPECT_EQ(m["reference_version"].get<int>(), 2);
  m.erase("reference_version");
  std::ofstream(meta) << m.dump();
  Result old = run(resume);
  EXPECT_NE(old.exit_code, 0);
  EXPECT_EQ(old.output, "lucent: " + meta + ": cannot resume: the reference was rendered by version 1 of the "
                        "references' estimators, this lucent renders version 2; its samples estimate another image: "
                        "render it anew\n");
  // Another scene under the same file name.
  ASSERT_EQ(run(render).exit_code, 0);
  std::ofstream(scene) << std::string(text).replace(text.find("Skin1"), 5, "Marble");
  Result edited = run(resume);
  EXPECT_NE(edited.exit_code, 0);
  EXPECT_NE(edited.output.find("cannot resume: the reference has scene_hash"), std::string::npos) << edited.output;
}

// A bssrdf reference integrates the objects' models; a scene file that names none leaves them to the default, so
// the same file can mean another image under another default. The models are recorded, and a reference of other
// models (or of unrecorded ones) is neither resumed nor reused by the bench's cache.
TEST(CliReferences, ABssrdfReferenceOfOtherModelsIsNeitherResumedNorReused) {
  auto dir = references_dir();
  const std::string scene = (dir / "models_sphere.json").string(), exr = (dir / "models.exr").string(),
                    meta = (dir / "models.meta.json").string();
  std::ofstream(scene) << R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]},
    "lights": [{"direction": [0, 0, -1]}], "objects": [{"shape": "sphere", "material": "Skin1"}],
    "render": {"width": 12, "height": 8}})";
  ASSERT_EQ(run("reference " + scene + " --integrator bssrdf --spp 2 -q -o " + exr).exit_code, 0);
  nlohmann::json m = nlohmann::json::parse(std::ifstream(meta));
  EXPECT_EQ(m["models"], std::string(lucent::to_string(lucent::kDefaultBssrdfModel)));
  m["models"] = "directional";  // as if rendered when the default was another model
  std::ofstream(meta) << m.dump();
  Result resumed = run("reference " + scene + " --integrator bssrdf --spp 2 -q --resume -o " + exr);
  EXPECT_NE(resumed.exit_code, 0);
  EXPECT_EQ(resumed.output, "lucent: " + meta + ": cannot resume: the reference integrates the models \"directional\", "
                            "this run " + std::string(lucent::to_string(lucent::kDefaultBssrdfModel)) +
                            "; render it anew\n");
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(meta))["samples_per_pixel"].get<int>(), 2);  // left as it was

  // The bench's cache: an entry of other models is rendered anew beside it, not returned.
  const std::string cache = (dir / "models_cache").string();
  std::filesystem::remove_all(cache);
  std::filesystem::create_directories(cache);
  const lucent::reference::ReferenceImage a = lucent::reference::cached_reference(cache, scene, {}, "bssrdf", 2, {});
  for (const auto& entry : std::filesystem::directory_iterator(cache)) {
    if (!entry.path().string().ends_with(".meta.json")) continue;
    nlohmann::json cm = nlohmann::json::parse(std::ifstream(entry.path()));
    EXPECT_EQ(cm["models"], std::string(lucent::to_string(lucent::kDefaultBssrdfModel)));
    cm["models"] = "directional";
    std::ofstream(entry.path()) << cm.dump();
    const lucent::reference::ReferenceImage b = lucent::reference::cached_reference(cache, scene, {}, "bssrdf", 2, {});
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(entry.path()))["models"],
              std::string(lucent::to_string(lucent::kDefaultBssrdfModel)))
        << "the entry of other models was returned instead of rendered anew";
    EXPECT_EQ(a.samples_per_pixel, b.samples_per_pixel);
  }
}

TEST(CliReferences, BadInputsNameTheInput) {
  Result integrator = run("reference /nonexistent.json --integrator photon");
  EXPECT_EQ(integrator.output, "lucent: --integrator: 'photon' is not one of volpath, bssrdf\n");
  Result scene = run("reference /nonexistent/scene.json");
  EXPECT_EQ(scene.output, "lucent: /nonexistent/scene.json: cannot open scene file\n");
  Result compare = run("compare /nonexistent/a.exr /nonexistent/b.exr");
  EXPECT_NE(compare.exit_code, 0);
  EXPECT_EQ(compare.output.rfind("lucent: /nonexistent/a.exr: cannot read EXR:", 0), 0u) << compare.output;
}

// `compare` over an image with a NaN printed RMSE nan and PSNR 1e9 with exit 0: now one line naming the file,
// the pixel and the band, and a non-zero exit.
TEST(CliReferences, CompareRefusesNonFiniteImages) {
  auto dir = references_dir();
  const std::string good = (dir / "finite.exr").string(), bad = (dir / "nan.exr").string();
  lucent::ImageRGBA32F image{3, 2, std::vector<float>(3 * 2 * 4, 0.5f)};
  lucent::write_exr(good, image);
  image.pixels[4 * (1 * 3 + 2)] = std::nanf("");  // pixel (2, 1), red
  lucent::write_exr(bad, image);
  Result compare = run("compare " + bad + " " + good);
  EXPECT_NE(compare.exit_code, 0);
  EXPECT_EQ(compare.output, "lucent: " + bad + " has a non-finite value nan at pixel (2, 1), red; no error metric "
                            "is computed over it\n");
  EXPECT_NE(run("compare " + good + " " + bad).exit_code, 0);
  EXPECT_EQ(run("compare " + good + " " + good).exit_code, 0);
}

// `tonemap` turned a NaN into black without a word; +inf is as bright as it gets: white.
TEST(CliReferences, TonemapRefusesNaNAndShowsInfinityAsWhite) {
  auto dir = references_dir();
  const std::string exr = (dir / "tonemap_in.exr").string(), png = (dir / "tonemap_out.png").string();
  lucent::ImageRGBA32F image{2, 1, {0.5f, 0.5f, 0.5f, 1, std::numeric_limits<float>::infinity(), 1e38f, 3e38f, 1}};
  lucent::write_exr(exr, image);
  Result ok = run("tonemap " + exr + " -o " + png);
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  const lucent::ImageRGBA8 shown = lucent::read_png(png);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(shown.at(1, 0)[c], 255) << c;
  image.pixels[1] = std::nanf("");
  lucent::write_exr(exr, image);
  Result nan = run("tonemap " + exr + " -o " + png);
  EXPECT_NE(nan.exit_code, 0);
  EXPECT_EQ(nan.output, "lucent: " + exr + " has a NaN at pixel (0, 0), green: it has no colour to display\n");
}

// A bad override in the last variant is reported before anything renders (no GL context is needed to see it),
// naming the configuration, the variant and the override.
TEST(CliReferences, BenchChecksEveryVariantsSceneFirst) {
  auto dir = references_dir();
  std::string scene = (dir / "bench_sphere.json").string(), config = (dir / "bench_bad_variant.json").string();
  std::ofstream(scene) << R"({"lights": [{"direction": [0, -1, 0]}],
                              "objects": [{"shape": "sphere", "material": "Skin1"}]})";
  std::ofstream(config) << R"({"runs": [{"name": "a", "scene": ")" << scene
                        << R"(", "variants": [{"name": "fine"}, {"name": "bad", "set": ["method.K=0"]}]}]})";
  Result r = run("bench " + config + " -o " + (dir / "bench_bad_out").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.output, "lucent: " + config +
                          ": /runs/0/variants/1: --set 'method.K=0': /method/K: 0 is out of range; allowed range [1, 64] "
                          "maps\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "bench_bad_out" / "results.json"));
}

}  // namespace
