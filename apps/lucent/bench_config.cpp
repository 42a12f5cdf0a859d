// bench_config.cpp: see bench_config.h. The keys are declared like the scene file's (ParamDecl), so types, ranges
// and unknown keys get the scene parser's messages.
#include "bench_config.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "lucent/error.h"
#include "params/param_json.h"

namespace lucent::cli {
namespace {

using nlohmann::json;

constexpr double kMaxSpp = 1 << 30;

constexpr ParamDecl kBenchParams[] = {
    {"description", ParamType::String, "\"\"", "", 0, 0, "", "what the matrix measures, free text"},
    {"warmup_frames", ParamType::Int, "0", "frames", 0, 1e3, "",
     "every variant's frames rendered and discarded first (the method then restarts): timings of warm frames"},
    {"record_refusals", ParamType::Bool, "false", "", 0, 1, "",
     "a variant whose method refuses its scene is recorded with the method's message instead of stopping the bench"},
};
constexpr ParamDecl kReferenceParams[] = {
    {"spp", ParamType::Int, "256", "samples/pixel", 1, kMaxSpp, "", "samples per pixel of the first reference"},
    {"noise_ratio", ParamType::Float, "0", "", 0, 1e6, "",
     "refine until the reference's noise is this many times below the smallest noise-corrected RMSE (0: no refinement)"},
    {"max_spp", ParamType::Int, "", "samples/pixel", 1, kMaxSpp, "", "refinement stops here (default: spp)"},
    {"rmse_floor", ParamType::Float, "0.001", "", 0, 1e3, "", "errors below this are not resolved further"},
};
constexpr ParamDecl kRunParams[] = {
    {"name", ParamType::String, "", "", 0, 0, "", "run name (default: the scene file's stem)"},
    {"scene", ParamType::String, "", "", 0, 0, "", "scene file (required)"},
    {"restart_every_frame", ParamType::Bool, "false", "", 0, 1, "", "recompute cached state every frame"},
};
constexpr ParamDecl kVariantParams[] = {
    {"name", ParamType::String, "\"default\"", "", 0, 0, "", "variant name in the tables"},
    {"id", ParamType::String, "", "", 0, 0, "", "file stem of its images (default: the name)"},
    {"frames", ParamType::Int, "", "frames", 1, 1e6, "", "frames rendered (default: the scene's render.frames)"},
    {"equal_time", ParamType::Bool, "false", "", 0, 1, "", "also measure a bssrdf reference given the same time"},
    {"restart_every_frame", ParamType::Bool, "false", "", 0, 1, "", "recompute cached state every frame"},
    {"warmup_frames", ParamType::Int, "", "frames", 0, 1e3, "",
     "frames rendered and discarded first (then the method restarts), so the measured frames are warm (default: the "
     "configuration's, else 0)"},
};
constexpr ParamDecl kRegionParams[] = {
    {"name", ParamType::String, "", "", 0, 0, "", "region name in the tables (required)"},
    {"object", ParamType::String, "", "", 0, 0, "", "the scene object whose pixels form the region (required)"},
    {"center", ParamType::Vec3, "[0, 0, 0]", "units", -1e9, 1e9, "", "centre of the region's ball"},
    {"radius", ParamType::Float, "1e30", "units", 0, 1e30, "", "pixels whose first hit lies within this distance"},
    {"min_radius", ParamType::Float, "0", "units", 0, 1e30, "", "and at least this far from the centre"},
};
constexpr ParamDecl kPlotParams[] = {
    {"output", ParamType::String, "", "", 0, 0, "", "PNG written into the output folder (required)"},
    {"script", ParamType::String, "", "", 0, 0, "", "gnuplot script (required)"},
};

void require_key(const json& object, const char* key, const JsonLocation& where, const char* what) {
  if (!object.contains(key)) fail(where.child(key), fmt::format("missing; {}", what));
}

void require_array(const json& value, const JsonLocation& where, const char* of) {
  if (!value.is_array()) fail(where, fmt::format("expected an array of {}, got {}", of, excerpt(value)));
}

// "set": ["render.width=160", "objects.0.material.model=\"standard\"", ...]; what the values mean is checked when
// the scenes are loaded.
void check_overrides(const json& object, const JsonLocation& where) {
  if (!object.contains("set")) return;
  const JsonLocation at = where.child("set");
  require_array(object["set"], at, "\"key=value\" strings");
  for (std::size_t i = 0; i < object["set"].size(); ++i) {
    const json& s = object["set"][i];
    if (!s.is_string() || s.get<std::string>().find('=') == 0 || s.get<std::string>().find('=') == std::string::npos)
      fail(at.child(i), fmt::format("expected \"key=value\", got {}", excerpt(s)));
  }
}

// Run names and variant ids name the bench's image files: letters, digits, '_', '-', '.', not starting with '.', so
// that no name writes outside the output folder or over a hidden file; never '+', which joins them in an image's
// name (command_bench.cpp), so that no two images share one.
void require_file_name_part(const std::string& name, const JsonLocation& where, const char* what) {
  const bool safe = !name.empty() && name.size() <= 100 && name[0] != '.' &&
                    std::all_of(name.begin(), name.end(), [](unsigned char c) {
                      return std::isalnum(c) || c == '_' || c == '-' || c == '.';
                    });
  if (!safe)
    fail(where, fmt::format("{} '{}' names image files: use letters, digits, '_', '-' and '.' (not first), at most 100",
                            what, text_excerpt(name)));
}

// A list of variants (a run's, or the configuration's shared by the runs without their own): keys, overrides and
// ids unique within the list, since ids name image files.
void check_variants(const json& variants, const JsonLocation& at) {
  require_array(variants, at, "variants");
  std::map<std::string, std::size_t> ids;
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const json& variant = variants[v];
    const JsonLocation vat = at.child(v);
    read_params(variant, {"variant", kVariantParams}, vat, {"set"});
    check_overrides(variant, vat);
    const std::string id = variant.value("id", variant.value("name", std::string("default")));
    require_file_name_part(id, vat, "variant id");
    if (auto [other, inserted] = ids.emplace(id, v); !inserted)
      fail(vat, fmt::format("variant id '{}' is also the id of variant {} (their images would overwrite each other)",
                            text_excerpt(id), other->second));
  }
}

}  // namespace

json run_variants(const json& config, const json& run) {
  if (run.contains("variants")) return run["variants"];
  if (config.contains("variants")) return config["variants"];
  return json::array({json::object()});
}

std::string run_name(const json& run) {
  if (run.contains("name")) return run["name"].get<std::string>();
  return std::filesystem::path(run.at("scene").get<std::string>()).stem().string();
}

void validate_bench_config(const json& config, const std::string& path) {
  const JsonLocation root{path, ""};
  read_params(config, {"bench", kBenchParams}, root, {"set", "references", "runs", "plots", "variants"});
  check_overrides(config, root);
  require_key(config, "runs", root, "an array of runs, each {\"scene\": ..., \"variants\": [...]}");
  if (!config["runs"].is_array()) throw Error(fmt::format("{}: \"runs\" must be an array of runs", path));

  std::map<std::string, std::size_t> runs;  // name -> index
  for (std::size_t i = 0; i < config["runs"].size(); ++i) {
    const json& run = config["runs"][i];
    const JsonLocation at = root.child("runs").child(i);
    read_params(run, {"run", kRunParams}, at, {"set", "variants", "regions"});
    require_key(run, "scene", at, "the scene file of this run");
    check_overrides(run, at);
    const std::string name = run_name(run);
    require_file_name_part(name, run.contains("name") ? at.child("name") : at.child("scene"), "run name");
    if (auto [other, inserted] = runs.emplace(name, i); !inserted)
      fail(at, fmt::format("run name '{}' is also the name of /runs/{}", text_excerpt(name), other->second));
    if (run.contains("regions")) {
      require_array(run["regions"], at.child("regions"), "regions");
      std::map<std::string, std::size_t> regions;
      for (std::size_t k = 0; k < run["regions"].size(); ++k) {
        const JsonLocation rat = at.child("regions").child(k);
        read_params(run["regions"][k], {"region", kRegionParams}, rat);
        require_key(run["regions"][k], "name", rat, "the region's name in the tables");
        require_key(run["regions"][k], "object", rat, "the name of a scene object, e.g. \"table\"");
        require_file_name_part(run["regions"][k]["name"].get<std::string>(), rat.child("name"), "region name");
        if (auto [other, inserted] = regions.emplace(run["regions"][k]["name"].get<std::string>(), k); !inserted)
          fail(rat.child("name"), fmt::format("also the name of region {}", other->second));
      }
    }
    if (run.contains("variants")) check_variants(run["variants"], at.child("variants"));
  }
  if (config.contains("variants")) check_variants(config["variants"], root.child("variants"));

  if (config.contains("references")) {
    const JsonLocation at = root.child("references");
    require_object(config["references"], at);
    for (const auto& [integrator, spec] : config["references"].items()) {
      const JsonLocation iat = at.child(integrator);
      if (integrator != "bssrdf" && integrator != "volpath") fail(iat, "unknown integrator; known: bssrdf, volpath");
      read_params(spec, {"reference", kReferenceParams}, iat, {"only_runs"});
      const int spp = spec.value("spp", 256);
      if (spec.contains("max_spp") && spec["max_spp"].get<int>() < spp)
        fail(iat.child("max_spp"), fmt::format("{} is below spp {}", spec["max_spp"].get<int>(), spp));
      if (!spec.contains("only_runs")) continue;
      require_array(spec["only_runs"], iat.child("only_runs"), "run names");
      for (std::size_t k = 0; k < spec["only_runs"].size(); ++k) {
        const json& name = spec["only_runs"][k];
        if (!name.is_string() || !runs.count(name.get<std::string>()))
          fail(iat.child("only_runs").child(k), fmt::format("{} is not the name of a run", excerpt(name)));
      }
    }
  }

  if (config.contains("plots")) {
    require_array(config["plots"], root.child("plots"), "plots");
    for (std::size_t i = 0; i < config["plots"].size(); ++i) {
      const JsonLocation at = root.child("plots").child(i);
      const json& plot = config["plots"][i];
      read_params(plot, {"plot", kPlotParams}, at);
      require_key(plot, "output", at, "the PNG to write, e.g. \"fig13.png\"");
      require_key(plot, "script", at, "a gnuplot script, e.g. \"bench/fig13.gp\"");
      const std::string script = plot["script"].get<std::string>();
      if (!std::filesystem::exists(script))
        fail(at.child("script"), fmt::format("{}: no such file", text_excerpt(script)));
    }
  }
}

}  // namespace lucent::cli
