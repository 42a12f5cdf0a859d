// test_reference_merge.cpp: `lucent reference merge`: batches rendered with distinct seeds combine into what one
// run of all their samples reports (exactly, from known samples; statistically, against a real render), and every
// merge that would not be one reference is refused with one line naming the input.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli_runner.h"
#include "lucent/image.h"
#include "reference/reference_files.h"
#include "reference/reference_merge.h"

namespace {

namespace fs = std::filesystem;
using lucent::test::CliResult;
using lucent::test::run_cli;
using nlohmann::json;

fs::path merge_dir() {
  auto dir = fs::temp_directory_path() / "lucent_reference_merge";
  fs::create_directories(dir);
  return dir;
}

std::string path(const std::string& name) { return (merge_dir() / name).string(); }

// A small translucent sphere: 16x12, most pixels on the sphere, some on the black background.
std::string write_scene(const std::string& name, const std::string& material = "Skin1") {
  const std::string scene = path(name);
  std::ofstream(scene) << R"({"scale_mm": 10, "camera": {"eye": [0, 0, 2.5]},
    "lights": [{"direction": [0, 0, -1]}], "objects": [{"shape": "sphere", "material": ")"
                       << material << R"("}], "render": {"width": 16, "height": 12}})";
  return scene;
}

void render(const std::string& scene, const std::string& exr, const std::string& options) {
  const CliResult r = run_cli("reference " + scene + " -q " + options + " -o " + exr);
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

json metadata(const std::string& exr) {
  return json::parse(std::ifstream(lucent::reference::reference_files(exr).metadata));
}

// The renderer's estimator, written out: mean and standard error sqrt(v / n), v the unbiased sample variance.
void estimate(const std::vector<double>& x, float& mean, float& standard_error) {
  const double n = static_cast<double>(x.size());
  double sum = 0.0, sum2 = 0.0;
  for (double v : x) sum += v, sum2 += v * v;
  const double m = sum / n;
  const double variance = n > 1 ? std::max(0.0, (sum2 - n * m * m) / (n - 1.0)) : 0.0;
  mean = static_cast<float>(m);
  standard_error = static_cast<float>(std::sqrt(variance / n));
}

// Exact: batches of known samples (1, 3 and 12 per pixel; unequal, so an unweighted mean or a pooled standard error
// would show) merge into the mean and standard error of all 16 samples, to float rounding.
TEST(ReferenceMerge, KnownSamplesMergeIntoTheEstimatorOfAllSamples) {
  const int width = 3, height = 2, pixels = width * height;
  const int counts[] = {1, 3, 12};
  std::mt19937_64 random(7);
  std::exponential_distribution<double> radiance(2.0);
  std::vector<std::vector<double>> all(static_cast<std::size_t>(pixels * 3));
  std::vector<std::string> inputs;
  for (int b = 0; b < 3; ++b) {
    lucent::reference::ReferenceImage image;
    image.mean = {width, height, std::vector<float>(static_cast<std::size_t>(pixels) * 4, 1.0f)};
    image.standard_error = {width, height, std::vector<float>(static_cast<std::size_t>(pixels) * 4, 0.0f)};
    image.samples_per_pixel = counts[b];
    image.seconds = 1.5 * (b + 1);
    for (int p = 0; p < pixels; ++p)
      for (int c = 0; c < 3; ++c) {
        std::vector<double> x;
        for (int s = 0; s < counts[b]; ++s) x.push_back(10.0 * b + radiance(random));  // batches differ in mean
        auto& everything = all[static_cast<std::size_t>(3 * p + c)];
        everything.insert(everything.end(), x.begin(), x.end());
        const auto k = static_cast<std::size_t>(4 * p + c);
        estimate(x, image.mean.pixels[k], image.standard_error.pixels[k]);
      }
    const std::string exr = path("known_" + std::to_string(b) + ".exr");
    lucent::reference::save_reference(lucent::reference::reference_files(exr), image,
                                      {{"scene", "known.json"}, {"integrator", "volpath"}, {"seed", 100 + b},
                                       {"width", width}, {"height", height}, {"overrides", json::array()}});
    inputs.push_back(exr);
  }
  const lucent::reference::StoredReference merged = lucent::reference::merge_references(inputs);
  EXPECT_EQ(merged.image.samples_per_pixel, 16);
  EXPECT_DOUBLE_EQ(merged.image.seconds, 1.5 + 3.0 + 4.5);
  EXPECT_EQ(merged.metadata["seeds"], json({100, 101, 102}));
  EXPECT_FALSE(merged.metadata.contains("seed"));
  ASSERT_EQ(merged.metadata["inputs"].size(), 3u);
  EXPECT_EQ(merged.metadata["inputs"][2]["samples_per_pixel"], 12);
  for (int p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) {
      float mean, standard_error;
      estimate(all[static_cast<std::size_t>(3 * p + c)], mean, standard_error);
      const auto k = static_cast<std::size_t>(4 * p + c);
      EXPECT_NEAR(merged.image.mean.pixels[k], mean, 1e-6 * std::abs(mean)) << "pixel " << p << " channel " << c;
      EXPECT_NEAR(merged.image.standard_error.pixels[k], standard_error, 1e-5 * standard_error)
          << "pixel " << p << " channel " << c;
    }
}

// Statistical, through the command line: two batches (seeds 1 and 2, 48 + 16 spp) against one render of 64 spp
// (seed 3). The means agree within the combined standard errors (mean z^2 near 1: 0.5 ... 2 over the ~400
// sphere pixel-channels); the reported standard errors, both estimates of sigma / sqrt(64) from 64 samples each, agree
// to 15% on the image mean (each pixel's estimate scatters by about 1 / sqrt(2 * 63) = 9%, heavier-tailed for
// path tracing, and the image mean averages ~400 of them; a merge that pooled the batches' standard errors as
// sqrt(SE1^2 + SE2^2) would be 1.6x too large, one that took the weighted mean of SEs 1.15-1.3x). Background
// pixels are exact in every render and must match exactly.
// Two renders of one image with independent samples (a merge and one run): per pixel and channel the difference
// over its combined standard error has a mean square near 1, and the two standard errors agree.
void expect_same_image_within_noise(const std::string& merged, const std::string& one);

TEST(ReferenceMerge, MergedBatchesMatchOneRenderOfAllSamples) {
  const std::string scene = write_scene("stat.json");
  const std::string a = path("stat_a.exr"), b = path("stat_b.exr"), one = path("stat_one.exr"),
                    merged = path("stat_merged.exr");
  render(scene, a, "--spp 48 --seed 1");
  render(scene, b, "--spp 16 --seed 2");
  render(scene, one, "--spp 64 --seed 3");
  const CliResult r = run_cli("reference merge " + a + " " + b + " -q -o " + merged);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
  const json meta = metadata(merged);
  EXPECT_EQ(meta["samples_per_pixel"], 64);
  EXPECT_NEAR(meta["seconds"].get<double>(), metadata(a)["seconds"].get<double>() + metadata(b)["seconds"].get<double>(),
              1e-12);
  EXPECT_EQ(meta["seeds"], json({1, 2}));
  EXPECT_EQ(meta["inputs"][0]["path"], a);
  EXPECT_EQ(meta["inputs"][1]["path"], b);

  expect_same_image_within_noise(merged, one);
}

// The batch recipe of docs/references.md run for real, with GNU parallel on this host instead of over ssh: four
// batches of 16 samples in two parallel jobs, merged, against one render of 64 samples.
TEST(ReferenceMerge, GnuParallelBatchesMergeIntoOneRender) {
  ASSERT_EQ(std::system("parallel --version > /dev/null 2>&1"), 0)
      << "GNU parallel is not installed (scripts/install-deps.sh installs it)";
  const std::string scene = write_scene("parallel.json");
  const std::string batch = path("parallel_batch.{}.exr");
  const std::string command =
      fmt::format("seq 1 4 | parallel -j 2 --halt now,fail=1 '{} reference {} --integrator volpath --spp 16 --seed {{}} "
                  "-q -o {}' 2>&1",
                  LUCENT_CLI, scene, batch);
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::string inputs;
  for (int i = 1; i <= 4; ++i) inputs += " " + path(fmt::format("parallel_batch.{}.exr", i));
  const std::string merged = path("parallel_merged.exr"), one = path("parallel_one.exr");
  const CliResult r = run_cli("reference merge" + inputs + " -q -o " + merged);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(metadata(merged)["seeds"], json({1, 2, 3, 4}));
  render(scene, one, "--integrator volpath --spp 64 --seed 9");
  expect_same_image_within_noise(merged, one);
}

void expect_same_image_within_noise(const std::string& merged, const std::string& one) {
  const lucent::ImageRGBA32F m = lucent::read_exr(merged),
                             m_se = lucent::read_exr(lucent::reference::reference_files(merged).standard_error);
  const lucent::ImageRGBA32F o = lucent::read_exr(one),
                             o_se = lucent::read_exr(lucent::reference::reference_files(one).standard_error);
  ASSERT_EQ(m.width, 16);
  ASSERT_EQ(m.height, 12);
  double z2 = 0.0, se_merged = 0.0, se_one = 0.0;
  int counted = 0, background = 0;
  for (std::size_t k = 0; k < m.pixels.size(); ++k) {
    if (k % 4 == 3) continue;
    const double combined = std::hypot(m_se.pixels[k], o_se.pixels[k]);
    if (combined == 0.0) {
      EXPECT_EQ(m.pixels[k], o.pixels[k]) << "pixel-channel " << k;
      ++background;
      continue;
    }
    const double z = (m.pixels[k] - o.pixels[k]) / combined;
    z2 += z * z;
    se_merged += m_se.pixels[k];
    se_one += o_se.pixels[k];
    ++counted;
  }
  ASSERT_GT(counted, 200);
  ASSERT_GT(background, 0);
  EXPECT_GT(z2 / counted, 0.5);
  EXPECT_LT(z2 / counted, 2.0);
  EXPECT_NEAR(se_merged / se_one, 1.0, 0.15);
}

// A batch merged with itself, or two batches of the same seed, hold the same samples: refused, nothing written.
TEST(ReferenceMerge, RefusesSamplesThatAreNotIndependent) {
  const std::string scene = write_scene("dup.json");
  const std::string a = path("dup_a.exr"), same_seed = path("dup_same_seed.exr"), b = path("dup_b.exr"),
                    out = path("dup_out.exr");
  render(scene, a, "--spp 2 --seed 4");
  render(scene, same_seed, "--spp 3 --seed 4");
  render(scene, b, "--spp 2 --seed 5");
  fs::remove(out);
  CliResult self = run_cli("reference merge " + a + " " + a + " -o " + out);
  EXPECT_EQ(self.exit_code, 1);
  EXPECT_EQ(self.output, "lucent: " + a + ": cannot merge: the same file as " + a +
                             " (a batch is not independent of itself)\n");
  CliResult seed = run_cli("reference merge " + a + " " + same_seed + " -o " + out);
  EXPECT_EQ(seed.exit_code, 1);
  EXPECT_EQ(seed.output, "lucent: " + same_seed + ": cannot merge: seed 4 is also the seed of " + a +
                             " (batches need distinct seeds to be independent)\n");
  // A merged reference holds its inputs' seeds: merging it again with one of them is refused too.
  const std::string ab = path("dup_ab.exr");
  ASSERT_EQ(run_cli("reference merge " + a + " " + b + " -q -o " + ab).exit_code, 0);
  CliResult again = run_cli("reference merge " + ab + " " + b + " -o " + out);
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_EQ(again.output, "lucent: " + b + ": cannot merge: seed 5 is also the seed of " + ab +
                              " (batches need distinct seeds to be independent)\n");
  // The output is never an input.
  CliResult onto = run_cli("reference merge " + a + " " + b + " -o " + b);
  EXPECT_EQ(onto.exit_code, 1);
  EXPECT_EQ(onto.output, "lucent: --output " + b + ": would overwrite the input " + b + "; choose another output path\n");
  EXPECT_FALSE(fs::exists(out));
}

// Batches of another image: another integrator, pixel sampling, scene content or override.
TEST(ReferenceMerge, RefusesBatchesOfAnotherImage) {
  const std::string scene = write_scene("image.json"), marble = write_scene("image_marble.json", "Marble");
  const std::string a = path("image_a.exr"), out = path("image_out.exr");
  render(scene, a, "--spp 2 --seed 1");
  fs::remove(out);
  auto refused = [&](const std::string& other, const std::string& problem) {
    const CliResult r = run_cli("reference merge " + a + " " + other + " -o " + out);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.output, "lucent: " + other + ": cannot merge: " + problem + "\n");
  };
  const std::string bssrdf = path("image_bssrdf.exr"), jitter = path("image_jitter.exr"),
                    other_scene = path("image_marble.exr"), scatter = path("image_scatter.exr"),
                    overridden = path("image_override.exr");
  render(scene, bssrdf, "--spp 2 --seed 2 --integrator bssrdf");
  refused(bssrdf, "integrator \"bssrdf\" differs from \"volpath\" in " + a);
  render(scene, jitter, "--spp 2 --seed 3 --jitter");
  refused(jitter, "jitter true differs from false in " + a);
  render(scene, scatter, "--spp 2 --seed 4 --max-scatter 1");
  refused(scatter, "max_scatter 1 differs from 0 in " + a);
  render(marble, other_scene, "--spp 2 --seed 5");
  refused(other_scene, "another scene (scene_hash " + metadata(other_scene)["scene_hash"].dump() + " differs from " +
                           metadata(a)["scene_hash"].dump() + " in " + a + ")");
  render(scene, overridden, "--spp 2 --seed 6 --set 'lights.0.radiance=[2,2,2]'");
  refused(overridden, "overrides [\"lights.0.radiance=[2,2,2]\"] differ from [] in " + a);
  const std::string wide = path("image_wide.exr");
  render(scene, wide, "--spp 2 --seed 7 --set render.width=20");
  refused(wide, "width 20 differs from 16 in " + a);
  EXPECT_FALSE(fs::exists(out));
  // The same scene content elsewhere (another host's copy) is the same scene.
  const std::string copy = path("image_copy.json"), moved = path("image_moved.exr");
  fs::copy_file(scene, copy, fs::copy_options::overwrite_existing);
  render(copy, moved, "--spp 2 --seed 8");
  const CliResult ok = run_cli("reference merge " + a + " " + moved + " -q -o " + out);
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

// Every input is three files: each missing one is named.
TEST(ReferenceMerge, RefusesAMissingFileOrCompanion) {
  const std::string scene = write_scene("missing.json");
  const std::string a = path("missing_a.exr"), b = path("missing_b.exr"), out = path("missing_out.exr");
  render(scene, a, "--spp 2 --seed 1");
  render(scene, b, "--spp 2 --seed 2");
  fs::remove(out);
  const std::string absent = path("missing_none.exr");
  fs::remove(absent);
  CliResult none = run_cli("reference merge " + a + " " + absent + " -o " + out);
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_EQ(none.output, "lucent: " + absent + ": no such file\n");
  fs::remove(path("missing_b.stderr.exr"));
  CliResult se = run_cli("reference merge " + a + " " + b + " -o " + out);
  EXPECT_EQ(se.exit_code, 1);
  EXPECT_EQ(se.output, "lucent: " + path("missing_b.stderr.exr") + ": no such file (the standard error written beside " +
                           b + ")\n");
  render(scene, b, "--spp 2 --seed 2");
  fs::remove(path("missing_b.meta.json"));
  CliResult meta = run_cli("reference merge " + a + " " + b + " -o " + out);
  EXPECT_EQ(meta.exit_code, 1);
  EXPECT_EQ(meta.output, "lucent: " + path("missing_b.meta.json") +
                             ": no such file (the metadata written beside the reference)\n");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace

namespace {

// Metadata written before the scene digest and the time were recorded: the scene is compared by its path, the time
// taken as 0.
TEST(ReferenceMerge, OlderMetadataComparesTheScenePath) {
  const std::string scene = write_scene("old.json"), copy = path("old_copy.json");
  fs::copy_file(scene, copy, fs::copy_options::overwrite_existing);
  const std::string a = path("old_a.exr"), b = path("old_b.exr"), c = path("old_c.exr"), out = path("old_out.exr");
  render(scene, a, "--spp 2 --seed 1");
  render(scene, b, "--spp 2 --seed 2");
  render(copy, c, "--spp 2 --seed 3");
  for (const std::string& exr : {a, b, c}) {
    json meta = metadata(exr);
    meta.erase("scene_hash");
    meta.erase("time_seconds");
    std::ofstream(lucent::reference::reference_files(exr).metadata) << meta.dump(2);
  }
  fs::remove(out);
  const CliResult ok = run_cli("reference merge " + a + " " + b + " -q -o " + out);
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_EQ(metadata(out)["samples_per_pixel"], 4);
  const CliResult other = run_cli("reference merge " + a + " " + c + " -o " + out);
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_EQ(other.output, "lucent: " + c + ": cannot merge: another scene (scene \"" + copy + "\" differs from \"" +
                              scene + "\" in " + a + ")\n");
}

// Sphere jumps change how volpath samples, not what it estimates: batches with and without them merge, each input
// keeps its setting, and the merged metadata claims neither (nor a steps-per-path statistic of one batch).
TEST(ReferenceMerge, BatchesWithAndWithoutSphereJumpsMerge) {
  const std::string scene = write_scene("jumps.json", "Marble");
  const std::string on = path("jumps_on.exr"), off = path("jumps_off.exr"), out = path("jumps_merged.exr");
  render(scene, on, "--spp 2 --seed 1");
  render(scene, off, "--spp 2 --seed 2 --sphere-jumps off");
  EXPECT_EQ(metadata(on)["sphere_jumps"], true);
  EXPECT_EQ(metadata(off)["sphere_jumps"], false);
  EXPECT_GT(metadata(on)["steps_per_path"].get<double>(), 0.0);
  const CliResult r = run_cli("reference merge -q " + on + " " + off + " -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json merged = metadata(out);
  EXPECT_FALSE(merged.contains("sphere_jumps"));
  EXPECT_FALSE(merged.contains("steps_per_path"));
  EXPECT_EQ(merged["inputs"][0]["sphere_jumps"], true);
  EXPECT_EQ(merged["inputs"][1]["sphere_jumps"], false);
  const CliResult wrong = run_cli("reference " + scene + " -q --spp 1 --sphere-jumps maybe -o " + path("jumps_x.exr"));
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_EQ(wrong.output, "lucent: --sphere-jumps: 'maybe' is not one of on, off\n");
}

}  // namespace
