// test_bench_config.cpp: a `lucent bench` configuration is checked before anything renders: exact messages for
// unknown keys, wrong types, out-of-range values, duplicate names and missing files; every shipped bench/*.json
// passes.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench_config.h"
#include "params/param_json.h"
#include "../test_support.h"
#include "../test_paths.h"

namespace {

using lucent::cli::validate_bench_config;
using nlohmann::json;

// The message for `text` as the file "b.json", or "" when it is valid; read as `lucent bench` reads it.
std::string problem(const std::string& text) {
  return lucent::test::error_message(
      [&] { validate_bench_config(lucent::parse_json(text, {"b.json", ""}), "b.json"); });
}

const char* kRun = R"({"name": "marble", "scene": "scenes/bunny_marble.json"})";

std::string with_run(const std::string& run_text) { return R"({"runs": [)" + run_text + "]}"; }

TEST(BenchConfig, ShippedConfigurationsAreValid) {
  const std::filesystem::path bench = std::filesystem::path(LUCENT_SCENES_DIR).parent_path() / "bench";
  int checked = 0;
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(bench.parent_path());  // plot scripts are named relative to the repository
  for (const auto& entry : std::filesystem::directory_iterator(bench)) {
    if (entry.path().extension() != ".json") continue;
    EXPECT_EQ(lucent::test::error_message([&] {
                validate_bench_config(json::parse(std::ifstream(entry.path())), entry.path().string());
              }),
              "");
    ++checked;
  }
  std::filesystem::current_path(cwd);
  EXPECT_GE(checked, 6);
}

// Run names and variant ids become file names of the bench's images: none may leave the output folder.
TEST(BenchConfig, RunNamesAndVariantIdsAreSafeFileNames) {
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "name": "../../escape"})")),
            "b.json: /runs/0/name: run name '../../escape' names image files: use letters, digits, '_', '-' and '.' "
            "(not first), at most 100");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "variants": [{"id": "a/b"}]})")),
            "b.json: /runs/0/variants/0: variant id 'a/b' names image files: use letters, digits, '_', '-' and '.' "
            "(not first), at most 100");
}

TEST(BenchConfig, UnknownKeysAreNamedWithTheKnownOnes) {
  EXPECT_EQ(problem(R"({"run": []})"),
            "b.json: /run: unknown key; known keys: description, warmup_frames, record_refusals, set, references, runs, "
            "plots, variants");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "varients": []})")),
            "b.json: /runs/0/varients: unknown key; known keys: name, scene, restart_every_frame, set, variants, regions");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "variants": [{"frame": 4}]})")),
            "b.json: /runs/0/variants/0/frame: unknown key; known keys: name, id, frames, equal_time, "
            "restart_every_frame, warmup_frames, set");
  EXPECT_EQ(problem(R"({"runs": [], "references": {"volpth": {"spp": 4}}})"),
            "b.json: /references/volpth: unknown integrator; known: bssrdf, volpath");
  EXPECT_EQ(problem(R"({"runs": [], "references": {"bssrdf": {"sp": 4}}})"),
            "b.json: /references/bssrdf/sp: unknown key; known keys: spp, noise_ratio, max_spp, rmse_floor, only_runs");
}

TEST(BenchConfig, TypesAndRanges) {
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "variants": [{"frames": "x"}]})")),
            "b.json: /runs/0/variants/0/frames: expected a number, got \"x\"");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "variants": [{"frames": 0}]})")),
            "b.json: /runs/0/variants/0/frames: 0 is out of range; allowed range [1, 1e+06] frames");
  EXPECT_EQ(problem(R"({"runs": [], "references": {"bssrdf": {"spp": -4}}})"),
            "b.json: /references/bssrdf/spp: -4 is out of range; allowed range [1, 1.07374e+09] samples/pixel");
  EXPECT_EQ(problem(R"({"runs": [], "references": {"volpath": {"spp": 2.5}}})"),
            "b.json: /references/volpath/spp: 2.5 is not an integer");
  EXPECT_EQ(problem(R"({"runs": [], "references": {"bssrdf": {"spp": 64, "max_spp": 32}}})"),
            "b.json: /references/bssrdf/max_spp: 32 is below spp 64");
  EXPECT_EQ(problem(R"({"runs": [], "references": {"bssrdf": {"noise_ratio": "nan"}}})"),
            "b.json: /references/bssrdf/noise_ratio: NaN is not allowed; allowed range [0, 1e+06]");
  EXPECT_EQ(problem(R"({"runs": {"name": "marble"}})"), "b.json: \"runs\" must be an array of runs");
  EXPECT_EQ(problem(R"({"runs": [3]})"), "b.json: /runs/0: expected a JSON object, got 3");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "variants": {"frames": 4}})")),
            "b.json: /runs/0/variants: expected an array of variants, got {\"frames\":4}");
}

TEST(BenchConfig, OverridesAreKeyValueStrings) {
  EXPECT_EQ(problem(R"({"set": ["render.width"], "runs": []})"),
            "b.json: /set/0: expected \"key=value\", got \"render.width\"");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "set": ["=3"]})")),
            "b.json: /runs/0/set/0: expected \"key=value\", got \"=3\"");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "variants": [{"set": [4]}]})")),
            "b.json: /runs/0/variants/0/set/0: expected \"key=value\", got 4");
}

TEST(BenchConfig, MissingScenesAndDuplicateNames) {
  EXPECT_EQ(problem(R"({})"),
            "b.json: /runs: missing; an array of runs, each {\"scene\": ..., \"variants\": [...]}");
  EXPECT_EQ(problem(with_run(R"({"name": "a"})")), "b.json: /runs/0/scene: missing; the scene file of this run");
  EXPECT_EQ(problem(with_run(std::string(kRun) + ", " + kRun)),
            "b.json: /runs/1: run name 'marble' is also the name of /runs/0");
  // Without names, two runs of the same scene file collide too.
  EXPECT_EQ(problem(with_run(R"({"scene": "a/bunny.json"}, {"scene": "b/bunny.json"})")),
            "b.json: /runs/1: run name 'bunny' is also the name of /runs/0");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "variants": [{"name": "one"}, {"id": "one"}]})")),
            "b.json: /runs/0/variants/1: variant id 'one' is also the id of variant 0 (their images would overwrite "
            "each other)");
  EXPECT_EQ(problem(R"({"runs": [)" + std::string(kRun) + R"(], "references": {"bssrdf": {"only_runs": ["marbel"]}}})"),
            "b.json: /references/bssrdf/only_runs/0: \"marbel\" is not the name of a run");
  EXPECT_EQ(problem(R"({"runs": [], "plots": [{"output": "a.png", "script": "/nonexistent/a.gp"}]})"),
            "b.json: /plots/0/script: /nonexistent/a.gp: no such file");
  EXPECT_EQ(problem(R"({"runs": [], "plots": [{"script": "/nonexistent/a.gp"}]})"),
            "b.json: /plots/0/output: missing; the PNG to write, e.g. \"fig13.png\"");
  EXPECT_EQ(problem(R"({"runs": [)" + std::string(kRun) + R"(], "references": {"bssrdf": {"only_runs": ["marble"]}}})"),
            "");
}

// The configuration's "variants" serve every run without its own: checked like a run's.
TEST(BenchConfig, SharedVariantsAreCheckedLikeARunsOwn) {
  EXPECT_EQ(problem(R"({"runs": [], "variants": [{"name": "one"}, {"id": "one"}]})"),
            "b.json: /variants/1: variant id 'one' is also the id of variant 0 (their images would overwrite each "
            "other)");
  EXPECT_EQ(problem(R"({"runs": [], "variants": [{"frames": 0}]})"),
            "b.json: /variants/0/frames: 0 is out of range; allowed range [1, 1e+06] frames");
  EXPECT_EQ(problem(R"({"runs": [], "variants": [{"set": ["K"]}]})"),
            "b.json: /variants/0/set/0: expected \"key=value\", got \"K\"");
  EXPECT_EQ(problem(R"({"runs": [], "variants": {"frames": 4}})"),
            "b.json: /variants: expected an array of variants, got {\"frames\":4}");
  EXPECT_EQ(problem(R"({"runs": [], "warmup_frames": -1})"),
            "b.json: /warmup_frames: -1 is out of range; allowed range [0, 1000] frames");
  EXPECT_EQ(problem(R"({"runs": [], "record_refusals": "yes"})"),
            "b.json: /record_refusals: expected true or false, got \"yes\"");
  const json config = json::parse(R"({"variants": [{"name": "shared"}], "runs": [{"scene": "a.json"},
      {"scene": "b.json", "variants": [{"name": "own"}]}, {"scene": "c.json"}]})");
  EXPECT_EQ(lucent::cli::run_variants(config, config["runs"][0]), config["variants"]);
  EXPECT_EQ(lucent::cli::run_variants(config, config["runs"][1]), config["runs"][1]["variants"]);
  EXPECT_EQ(lucent::cli::run_variants(json::parse(R"({"runs": []})"), config["runs"][2]),
            json::parse("[{}]"));
}

// A run's "regions" (measured on their own, e.g. the candle's table) name image files and table rows.
TEST(BenchConfig, RegionsHaveUniqueSafeNamesAndAnObject) {
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "regions": [{"name": "table", "object": "table", "radius": 5}]})")),
            "");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "regions": [{"name": "table"}]})")),
            "b.json: /runs/0/regions/0/object: missing; the name of a scene object, e.g. \"table\"");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "regions": [{"name": "t", "object": "a"}, {"name": "t", "object": "b"}]})")),
            "b.json: /runs/0/regions/1/name: also the name of region 0");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "regions": [{"name": "../t", "object": "a"}]})")),
            "b.json: /runs/0/regions/0/name: region name '../t' names image files: use letters, digits, '_', '-' and '.' "
            "(not first), at most 100");
  EXPECT_NE(problem(with_run(R"({"scene": "s.json", "regions": [{"name": "t", "object": "a", "radius": -1}]})")), "");
}

TEST(BenchConfig, ReadLikeEveryJsonInput) {
  EXPECT_EQ(problem("{\"runs\": [\n  {\"scene\": \"s.json\",\n   \"scene\": \"t.json\"}]}"),
            "b.json: /runs/0/scene: duplicate key (each key may appear once in an object)");
  EXPECT_EQ(problem("{\"runs\": []\n \"plots\": []}"),
            "b.json: malformed JSON: line 2, column 8: syntax error while parsing object - unexpected string literal; "
            "expected '}'");
  EXPECT_EQ(problem(R"({"description": )" + std::string(200, '[') + std::string(200, ']') + "}"),
            "b.json: /description/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/...: nested deeper than 128 levels");
  EXPECT_EQ(problem(with_run(R"({"scene": "s.json", "variants": [{"frames": ")" + std::string(1000, 'x') + "\"}]}")),
            "b.json: /runs/0/variants/0/frames: expected a number, got \"" + std::string(56, 'x') + "...");
}

}  // namespace
