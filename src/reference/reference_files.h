// reference_files.h: a reference image on disk, as `lucent reference` and `lucent bench` write it: the mean
// radiance EXR, its standard error beside it, and the metadata (samples per pixel, seconds, scene, integrator).
// The three are written as one set (lucent::OutputSet) so a resumed reference is never half updated.
#pragma once
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "reference/reference_renderer.h"

namespace lucent::reference {

// The paths of one reference: reference_files("out/ref.exr") is {out/ref.exr, out/ref.stderr.exr,
// out/ref.meta.json}. The metadata's ".meta.json" keeps it from landing on a scene file (out/ref.json).
struct ReferenceFiles {
  std::string mean;
  std::string standard_error;
  std::string metadata;
};
ReferenceFiles reference_files(const std::string& mean_exr);

// Writes the mean, the standard error and the metadata (`metadata` plus samples_per_pixel and seconds from
// `image`) as one set. Throws lucent::Error naming the file that cannot be written.
void save_reference(const ReferenceFiles& files, const ReferenceImage& image, nlohmann::json metadata);

// The metadata of a reference: an object with an integer samples_per_pixel in [1, INT_MAX]. References written before the
// ".meta.json" name kept it in <stem>.json, which is read when it holds reference metadata. nullopt when there is
// none; throws lucent::Error when the file exists but is malformed.
std::optional<nlohmann::json> read_reference_metadata(const ReferenceFiles& files);

// The reference and its metadata; throws lucent::Error naming the missing or malformed file.
struct StoredReference {
  ReferenceImage image;
  nlohmann::json metadata;
};
StoredReference load_reference(const ReferenceFiles& files);

}  // namespace lucent::reference
