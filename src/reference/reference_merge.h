// reference_merge.h: combines independent batches of one reference (the same scene and settings, distinct seeds,
// rendered anywhere) into the reference of all their samples, exactly: what one run of the summed samples reports,
// up to float rounding and the randomness of the samples themselves.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lucent/scene.h"
#include "reference/reference_files.h"

namespace lucent::reference {

// A stable digest of the bytes of every file the scene was read from (scene file, meshes, maps, volumes), in the
// order scene_input_files lists them: 32 hex digits, the same on every host for the same files wherever they lie.
std::string scene_content_hash(const Scene& scene);

// The diffusion model of each translucent object, in order ("standard,directional"): what a bssrdf reference
// integrates besides the scene's files. A material that names no model takes the default (kDefaultBssrdfModel),
// which the files do not record, so a bssrdf reference is reused or resumed only for the same models.
std::string scene_models(const Scene& scene);

// The seeds whose samples a reference holds: its "seeds" (a merged reference) or its "seed". Throws lucent::Error
// naming `path` when the metadata has neither.
std::vector<std::uint64_t> reference_seeds(const nlohmann::json& metadata, const std::string& path);

// Loads the references at `inputs` (mean EXRs; their .stderr.exr and .meta.json beside them) and merges them.
// Per pixel and channel, batch i of n_i samples with mean m_i and standard error s_i has the sample variance
// v_i = s_i^2 n_i (the renderer's unbiased estimator, v = (sum2 - n m^2) / (n - 1), SE = sqrt(v / n)); the merged
// mean is sum n_i m_i / N and the merged variance (sum (n_i - 1) v_i + sum n_i (m_i - m)^2) / (N - 1), which is
// the renderer's estimator over all N samples. Metadata: the first input's, with samples_per_pixel and seconds
// summed, "seeds" all the inputs' seeds, "inputs" one entry per input (path, seeds, samples, seconds).
// Throws lucent::Error("<input>: <problem>") for a missing file or companion, and unless every input renders the
// same image (integrator, scene content or path, relevant overrides, size, jitter, max_scatter, time) with seeds
// no other input used.
StoredReference merge_references(const std::vector<std::string>& inputs);

}  // namespace lucent::reference
