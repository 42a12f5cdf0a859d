// bench_config.h: the keys of a `lucent bench` configuration (bench/*.json), declared once and checked before
// anything is rendered, so that a misspelt key or a bad value in the last run of an hours-long matrix is one
// clear error at the start ("bench.json: /runs/2/variants/0/frames: 0 is out of range; ...") instead of a
// silently different matrix or an exception hours later.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace lucent::cli {

// Checks the configuration's structure, keys, types and ranges (see the declarations in bench_config.cpp):
// "runs" an array of objects with a "scene" each, unique run names and, within a run, unique variant ids;
// "references" only "bssrdf" and "volpath", max_spp >= spp, "only_runs" naming runs of the file; a run's
// "regions" each with a unique "name" and an "object"; "set" lists of
// "key=value" strings; "plots" with an "output" and an existing "script". Throws lucent::Error naming the file and
// the JSON path.
void validate_bench_config(const nlohmann::json& config, const std::string& path);

// The variants of a run: its own "variants", else the configuration's (shared by every run without its own), else
// one variant with no overrides.
nlohmann::json run_variants(const nlohmann::json& config, const nlohmann::json& run);

// The name of a run: its "name", or its scene file's stem.
std::string run_name(const nlohmann::json& run);

}  // namespace lucent::cli
