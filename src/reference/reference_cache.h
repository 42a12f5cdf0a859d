// reference_cache.h: converged references kept in a folder and reused across benchmark runs: keyed by the scene,
// the integrator and the overrides that change the image (not the method's parameters or frame counts), resumed
// with more samples when a run asks for more than the cache holds.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "reference/reference_renderer.h"

namespace lucent::reference {

// The overrides ("key=value") that change a reference's image: not "method.*", "method=" or "render.frames", and for
// volpath not the diffusion model ("*.model=") either (the physics does not use it), unless the scene at
// `scene_path` gives a material by its surface albedo (model_sets_coefficients). Sorted.
std::vector<std::string> relevant_overrides(const std::vector<std::string>& sets, const std::string& integrator,
                                            const std::string& scene_path = "");
// Whether the diffusion model can change what volpath renders of the scene: a material given by its surface albedo
// (with mfp_mm, by an albedo_map, or a glTF material through "from_mesh") has the coefficients of the model's
// inversion. Judged from the scene file's text and the overrides, conservatively: a mention of "mfp_mm" or
// "from_mesh" anywhere counts (a needless new reference at worst, never a wrong reuse).
bool model_sets_coefficients(const std::string& scene_path, const std::vector<std::string>& sets);
// "<integrator>_<16 hex digits>": the cache entry's file stem for the scene, integrator and relevant overrides.
std::string reference_key(const std::string& scene, const std::vector<std::string>& sets, const std::string& integrator);

// A reference of `scene_path` with `sets` applied and at least `spp` samples per pixel: the best cached one in
// `folder` when it has enough samples, else that one resumed (or a new one) and saved back. A damaged cache
// entry is ignored with a warning on stderr. `progress` receives the fraction done of a rendering.
ReferenceImage cached_reference(const std::string& folder, const std::string& scene_path,
                                const std::vector<std::string>& sets, const std::string& integrator, int spp,
                                const std::function<void(double)>& progress = {});

}  // namespace lucent::reference
