// reference_cache.cpp: see reference_cache.h.
#include "reference/reference_cache.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "lucent/warning.h"
#include "lucent/scene.h"
#include "io/input_file.h"
#include "reference/reference_files.h"
#include "reference/reference_merge.h"

namespace lucent::reference {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<std::string> strings(const json& j, const char* key) {
  std::vector<std::string> out;
  if (j.contains(key) && j.at(key).is_array())
    for (const auto& s : j.at(key))
      if (s.is_string()) out.push_back(s.get<std::string>());
  return out;
}

}  // namespace

bool model_sets_coefficients(const std::string& scene_path, const std::vector<std::string>& sets) {
  auto mentions = [](const std::string& text) {
    return text.find("mfp_mm") != std::string::npos || text.find("from_mesh") != std::string::npos;
  };
  if (std::any_of(sets.begin(), sets.end(), mentions)) return true;
  require_regular_file(scene_path);
  std::ifstream file(scene_path);
  std::stringstream text;
  text << file.rdbuf();
  return mentions(text.str());
}

std::vector<std::string> relevant_overrides(const std::vector<std::string>& sets, const std::string& integrator,
                                            const std::string& scene_path) {
  const bool model_matters = integrator != "volpath" || (!scene_path.empty() && model_sets_coefficients(scene_path, sets));
  std::vector<std::string> relevant;
  for (const std::string& s : sets) {
    bool method = s.rfind("method.", 0) == 0 || s.rfind("method=", 0) == 0 || s.rfind("render.frames", 0) == 0;
    bool model = !model_matters && s.find(".model=") != std::string::npos;
    if (!method && !model) relevant.push_back(s);
  }
  std::sort(relevant.begin(), relevant.end());
  return relevant;
}

std::string reference_key(const std::string& scene, const std::vector<std::string>& sets, const std::string& integrator) {
  std::string text = scene + "|" + integrator;
  for (const std::string& s : relevant_overrides(sets, integrator, scene)) text += "|" + s;
  return fmt::format("{}_{:016x}", integrator, std::hash<std::string>{}(text));
}

ReferenceImage cached_reference(const std::string& folder, const std::string& scene_path,
                                const std::vector<std::string>& sets, const std::string& integrator, int spp,
                                const std::function<void(double)>& progress) {
  fs::path exr = fs::path(folder) / (reference_key(scene_path, sets, integrator) + ".exr");
  // An entry is reused only for the same scene content (a scene file edited since, or a mesh or map it reads,
  // makes it stale) and the same version of the estimators.
  const Scene scene = load_scene(scene_path, sets);
  const std::string scene_hash = scene_content_hash(scene);
  const std::string models = scene_models(scene);
  std::optional<ReferenceImage> cached;
  std::error_code listing;
  for (const auto& entry : fs::directory_iterator(exr.parent_path(), listing)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".exr" || name.ends_with(".stderr.exr")) continue;
    // A damaged cache entry (bad metadata, wrong types, a truncated EXR) is ignored with a warning, never fatal.
    try {
      const ReferenceFiles files = reference_files(entry.path().string());
      const std::optional<json> m = read_reference_metadata(files);
      auto text = [&](const char* key) { return m->contains(key) && (*m)[key].is_string() ? (*m)[key].get<std::string>() : ""; };
      if (!m || text("scene") != scene_path || text("integrator") != integrator) continue;
      if (text("scene_hash") != scene_hash || reference_version(*m) != kReferenceVersion) continue;
      if (integrator == "bssrdf" && text("models") != models) continue;  // older entries record none: re-rendered
      if (relevant_overrides(strings(*m, "overrides"), integrator, scene_path) !=
          relevant_overrides(sets, integrator, scene_path))
        continue;
      if (cached && cached->samples_per_pixel >= (*m)["samples_per_pixel"].get<int>()) continue;  // keep the best
      cached = load_reference(files).image;
      exr = entry.path();
    } catch (const std::exception& e) {
      warn(fmt::format("{}; that cached reference is ignored", e.what()));
    }
  }
  if (cached && cached->samples_per_pixel >= spp) return *cached;
  ReferenceSettings settings;
  settings.integrator = integrator == "volpath" ? Integrator::Volpath : Integrator::Bssrdf;
  settings.samples_per_pixel = spp - (cached ? cached->samples_per_pixel : 0);
  fmt::print(stderr, "  reference {} {} spp ({}x{}){}...\n", integrator, spp, scene.render.width, scene.render.height,
             cached ? fmt::format(", resuming from {} spp", cached->samples_per_pixel) : "");
  settings.progress = progress;
  ReferenceImage image = render_reference(scene, settings, cached ? &*cached : nullptr);
  if (cached) image.seconds += cached->seconds;
  save_reference(reference_files(exr.string()), image,
                 {{"scene", scene_path},
                  {"scene_hash", scene_hash},
                  {"reference_version", kReferenceVersion},
                  {"overrides", sets},
                  {"integrator", integrator},
                  {"models", models}});
  return image;
}

}  // namespace lucent::reference
