// test_cli_references.cpp: `lucent slab`, `lucent reference` and `lucent compare` from outside: exact errors for
// bad input, the files a reference run writes, and compare's numbers on an image against itself.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <vector>
#include <csignal>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "reference/reference_cache.h"
#include "reference/reference_renderer.h"
#include "lucent/scene.h"
#include "../cli_runner.h"
#include "lucent/image.h"
#include "progress_bar.h"
#include "sample_progress.h"
#include "../child_exit.h"
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

// `lucent slab --model multipole`: the multipole model's totals of the same slab beside exact transport's, within
// 5% at reduced albedo 0.99 (2 mean free paths, eta 1.4: measured 1.021 and 0.983); the transport's transmittance
// is the diffuse one, the unscattered light removed. A dark medium or another model: one line, exit 1.
TEST(CliReferences, SlabPrintsTheMultipoleModelsTotals) {
  Result ok = run("slab --albedo 0.99 --eta 1.4 --thickness 2 --photons 20000 --model multipole --json");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  auto j = nlohmann::json::parse(ok.output);
  const double refracted = 1.0 - j["specular_reflectance"]["mean"].get<double>();
  const double T = (j["transmittance"]["mean"].get<double>() - j["unscattered_transmittance"]["mean"].get<double>()) /
                   refracted;
  EXPECT_NEAR(j["model"]["transport_diffuse_transmittance_per_refracted"]["mean"].get<double>(), T, 1e-9);
  EXPECT_NEAR(j["model"]["diffuse_reflectance_per_refracted"].get<double>() /
                  j["diffuse_reflectance_per_refracted"]["mean"].get<double>(), 1.0, 0.05);
  EXPECT_NEAR(j["model"]["diffuse_transmittance_per_refracted"].get<double>() / T, 1.0, 0.05);
  Result other = run("slab --albedo 0.9 --model standard");
  EXPECT_NE(other.exit_code, 0);
  EXPECT_EQ(other.output, "lucent: --model: 'standard' is not multipole (the half-space models' totals: lucent materials)\n");
  Result white = run("slab --albedo 1 --model multipole");
  EXPECT_NE(white.exit_code, 0);
  EXPECT_EQ(white.output, "lucent: --model multipole: the reduced albedo 1 is outside (0, 1)\n");
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
  EXPECT_EQ(m["reference_version"].get<int>(), lucent::reference::kReferenceVersion);
  m.erase("reference_version");
  std::ofstream(meta) << m.dump();
  Result old = run(resume);
  EXPECT_NE(old.exit_code, 0);
  EXPECT_EQ(old.output, "lucent: " + meta + ": cannot resume: the reference was rendered by version 1 of the "
                        "references' estimators, this lucent renders version " + std::to_string(lucent::reference::kReferenceVersion) +
                            "; its samples estimate another image: "
                        "render it anew\n");
  // A GPU batch is not resumed on the CPU (the file would be labelled gpu or cpu and hold both estimators).
  ASSERT_EQ(run(render).exit_code, 0);
  m = nlohmann::json::parse(std::ifstream(meta));
  m["device"] = "gpu";
  std::ofstream(meta) << m.dump();
  Result gpu = run(resume);
  EXPECT_NE(gpu.exit_code, 0);
  EXPECT_EQ(gpu.output, "lucent: " + meta + ": cannot resume: the reference was rendered on the gpu; render the other "
                        "samples as a batch of their own (another --seed) and combine both with lucent reference "
                        "merge\n");
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

namespace cli_progress {

// A reference's passes: each at most an eighth of the samples before it, at least one, ending at exactly `wanted`,
// as the renderer reports them (pass_done) on an image one row tall and when adding to an earlier run.
TEST(CliReferences, PassesGrowByAnEighthAsTheRendererReportsThem) {
  const auto path = references_dir() / "one_row.json";
  std::ofstream(path) << R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]},
    "lights": [{"direction": [0, 0, -1]}], "objects": [{"shape": "sphere", "material": "Skin1"}],
    "render": {"width": 3, "height": 1}})";
  const lucent::Scene scene = lucent::load_scene(path.string(), {});
  lucent::reference::ReferenceSettings settings;
  settings.integrator = lucent::reference::Integrator::Bssrdf;
  settings.samples_per_pixel = 40;
  std::vector<int> reported;
  settings.pass_done = [&](int done) { reported.push_back(done); };
  const lucent::reference::ReferenceImage first = lucent::reference::render_reference(scene, settings);
  EXPECT_EQ(reported, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 18, 20, 22, 24, 27, 30,
                                        33, 37, 40}));
  reported.clear();
  settings.samples_per_pixel = 25;
  lucent::reference::render_reference(scene, settings, &first);
  EXPECT_EQ(reported, (std::vector<int>{5, 10, 16, 23, 25}));  // passes of 40/8, 45/8, 50/8, 56/8, then the rest
  EXPECT_EQ(lucent::reference::reference_pass_size(80, 25), 10);
  EXPECT_EQ(lucent::reference::reference_pass_size(0, 4), 1);
  EXPECT_EQ(lucent::reference::reference_pass_size(800, 3), 3);
}

// The time left comes from the seconds per sample of the completed passes after the first (whose time holds the
// setup), not from the fraction of rows done: a run of 5 s setup and 2 s per sample per pixel.
TEST(CliReferences, TimeLeftFollowsMeasuredSecondsPerSample) {
  lucent::cli::SampleEta eta(0, 40);
  auto at = [](int samples) { return 5.0 + 2.0 * samples; };  // the second the pass ending at `samples` ends
  EXPECT_FALSE(eta.seconds_left(3.0).has_value());
  eta.update(0.6 / 40.0);  // 60% of the first pass's rows: no sample done yet
  EXPECT_EQ(eta.samples_done(), 0);
  EXPECT_FALSE(eta.seconds_left(4.0).has_value());
  EXPECT_NE(eta.text(4.0).find("0/40 spp  4.0 s elapsed, first pass 60% done"), std::string::npos) << eta.text(4.0);
  eta.pass_completed(1, at(1));
  EXPECT_EQ(eta.samples_done(), 1);
  EXPECT_DOUBLE_EQ(*eta.seconds_left(at(1)), 39.0 * 7.0);  // the first pass's 7 s, setup included: errs long
  eta.pass_completed(2, at(2));
  EXPECT_DOUBLE_EQ(*eta.seconds_left(at(2)), 38.0 * 2.0);
  for (int end : {3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 18, 20, 22, 24}) eta.pass_completed(end, at(end));
  EXPECT_EQ(eta.samples_done(), 24);
  EXPECT_DOUBLE_EQ(*eta.seconds_left(at(24)), 16.0 * 2.0);
  // Half-way through the pass 24 -> 27 (its rows reported): still 24 samples done, 3 s of the 32 spent.
  eta.update((24.0 + 1.5) / 40.0);
  EXPECT_EQ(eta.samples_done(), 24);
  EXPECT_DOUBLE_EQ(*eta.seconds_left(at(24) + 3.0), 29.0);
  EXPECT_NE(eta.text(at(24) + 3.0).find("24/40 spp  56.0 s elapsed, 29.0 s left"), std::string::npos);
  eta.pass_completed(40, at(40));
  EXPECT_DOUBLE_EQ(*eta.seconds_left(at(40)), 0.0);
}

TEST(CliReferences, DurationsReadAsSecondsMinutesHours) {
  EXPECT_EQ(lucent::cli::format_seconds(7.25), "7.2 s");
  EXPECT_EQ(lucent::cli::format_seconds(245.0), "4 min 05 s");
  EXPECT_EQ(lucent::cli::format_seconds(7620.0), "2 h 07 min");
}

}  // namespace cli_progress

TEST(CliReferences, VersionNamesTheProjectVersion) {
  Result version = run("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_TRUE(std::regex_match(version.output, std::regex("lucent [0-9]+\\.[0-9]+\\.[0-9]+( \\(git [^ ]+\\))?\n")))
      << version.output;
  EXPECT_EQ(version.output.rfind("lucent " LUCENT_PROJECT_VERSION, 0), 0u) << version.output;
}

// Identical images have no error: PSNR inf (was 1000000000.00 dB); a black reference has no peak: undefined; every
// other metric 0 and finite. JSON, which has no infinity, says so in "psnr".
TEST(CliReferences, CompareOfIdenticalAndBlackImagesPrintsInfAndUndefined) {
  auto dir = references_dir();
  const std::string grey = (dir / "grey.exr").string(), black = (dir / "black.exr").string();
  lucent::write_exr(grey, {2, 2, std::vector<float>(16, 0.25f)});
  lucent::write_exr(black, {2, 2, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}});
  for (const std::string& image : {grey, black}) {
    Result same = run("compare " + image + " " + image);
    ASSERT_EQ(same.exit_code, 0) << same.output;
    EXPECT_EQ(same.output.find("nan"), std::string::npos) << same.output;
    EXPECT_EQ(same.output.find("e+"), std::string::npos) << same.output;
    std::size_t rows = 0;
    for (std::size_t at = same.output.find("PSNR inf dB"); at != std::string::npos;
         at = same.output.find("PSNR inf dB", at + 1))
      ++rows;
    EXPECT_EQ(rows, 2u) << same.output;
    auto j = nlohmann::json::parse(run("compare " + image + " " + image + " --json").output);
    EXPECT_TRUE(j["linear"]["psnr_db"].is_null());
    EXPECT_EQ(j["linear"]["psnr"], "inf dB");
    EXPECT_EQ(j["display"]["relative_mse"].get<double>(), 0.0);
  }
  Result against_black = run("compare " + grey + " " + black);
  ASSERT_EQ(against_black.exit_code, 0) << against_black.output;
  EXPECT_NE(against_black.output.find("PSNR undefined (black reference)"), std::string::npos) << against_black.output;
  EXPECT_EQ(against_black.output.find("nan"), std::string::npos) << against_black.output;
}

// A PNG is decoded from sRGB: code 188 is display light 0.50289 (IEC 61966-2-1), compared with 0.5 in an EXR; its
// display values are the codes / 255. The output says that a PNG's numbers are not radiance.
TEST(CliReferences, CompareReadsPngAsDecodedSrgb) {
  auto dir = references_dir();
  const std::string png = (dir / "code188.png").string(), exr = (dir / "half.exr").string();
  lucent::write_png(png, {1, 1, {188, 188, 188, 255}});
  lucent::write_exr(exr, {1, 1, {0.5f, 0.5f, 0.5f, 1.0f}});
  Result result = run("compare " + png + " " + exr + " --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  auto j = nlohmann::json::parse(result.output);
  EXPECT_NEAR(j["linear"]["mean_error"].get<double>(), 0.502886 - 0.5, 1e-5);
  EXPECT_NE(j["note"].get<std::string>().find("not radiance"), std::string::npos);
  Result text = run("compare " + png + " " + png);
  EXPECT_NE(text.output.find("PSNR inf dB"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("not radiance"), std::string::npos) << text.output;
  Result other = run("compare " + png + " " + (dir / "x.tif").string());
  EXPECT_NE(other.exit_code, 0);
  EXPECT_EQ(other.output, "lucent: " + (dir / "x.tif").string() + ": compare reads .exr and .png images\n");
}

// SIGINT to a running reference saves the samples of its completed passes as a resumable set, and a run with
// --resume adds to them. The reference is started as a script's background job would be, SIGINT ignored: it takes
// SIGINT all the same (`kill -INT` did nothing before).
TEST(CliReferences, SigintSavesAResumableReference) {
  auto dir = references_dir() / "sigint";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string scene = (dir / "sphere.json").string(), exr = (dir / "ref.exr").string();
  const std::string log = (dir / "log.txt").string();
  std::ofstream(scene) << R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]},
    "lights": [{"direction": [0, 0, -1]}], "objects": [{"shape": "sphere", "material": "Skin1"}],
    "render": {"width": 12, "height": 8}})";
  const std::string command = fmt::format("trap '' INT; exec {} reference {} --spp 1000000000 -o {} 2> {}",
                                          LUCENT_CLI, scene, exr, log);
  std::vector<std::string> args = {"/bin/sh", "-c", command};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ), 0);
  // Wait for the progress line to show a completed pass (at most two minutes: a hung build fails, not hangs).
  auto spp_done = [&] {
    std::stringstream text;
    text << std::ifstream(log).rdbuf();
    std::smatch m;
    const std::string s = text.str();
    return std::regex_search(s, m, std::regex("([1-9][0-9]*)/1000000000 spp"));
  };
  for (int tries = 0; tries < 1200 && !spp_done(); ++tries) ::usleep(100000);
  ::kill(pid, SIGINT);
  const int status = lucent::test::wait_for_exit_or_kill(pid);
  std::stringstream output;
  output << std::ifstream(log).rdbuf();
  ASSERT_TRUE(WIFEXITED(status)) << output.str();
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT) << output.str();
  std::smatch m;
  const std::string text = output.str();
  ASSERT_TRUE(std::regex_search(text, m, std::regex("lucent: interrupted by SIGINT: saved ([0-9]+) of the 1000000000 "
                                                    "samples per pixel asked")))
      << text;
  const int saved = std::stoi(m[1].str());
  EXPECT_GE(saved, 1);
  auto meta = nlohmann::json::parse(std::ifstream(dir / "ref.meta.json"));
  EXPECT_EQ(meta["samples_per_pixel"].get<int>(), saved);
  EXPECT_TRUE(std::filesystem::exists(dir / "ref.stderr.exr"));
  Result resumed = run("reference " + scene + " --spp 2 -q --resume -o " + exr);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  meta = nlohmann::json::parse(std::ifstream(dir / "ref.meta.json"));
  EXPECT_EQ(meta["samples_per_pixel"].get<int>(), saved + 2);
}
