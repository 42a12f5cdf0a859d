// image_region.h: a part of an image chosen by what the camera sees there, for measuring one part of a scene
// separately (e.g. the table a candle's emergent light reaches, which is a few percent of the pixels and so
// hardly moves a whole-image RMSE). A pixel is in the region when its camera ray through the pixel centre (as
// rasterized, and as the references trace by default) first hits the named object within `radius` of `center`.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/image.h"
#include "lucent/scene.h"

namespace lucent::reference {

struct ImageRegion {
  std::string name;                // for tables
  std::string object;              // the scene object's name
  glm::dvec3 center{0.0};          // [scene units]
  double radius = 1e30;            // [scene units]
  double min_radius = 0.0;         // [scene units]; hits closer to `center` are left out
};

// One byte per pixel (1 = in the region), row-major with the top row first, scene.render.width x height.
// Throws lucent::Error when the scene has no object of that name.
std::vector<std::uint8_t> region_mask(const Scene& scene, const ImageRegion& region);

struct RegionMean {
  int pixels = 0;
  glm::dvec3 mean{0.0};            // linear radiance, per channel
  glm::dvec3 standard_error{0.0};  // of the mean, from a per-pixel standard-error image (0 without one)
  double display = 0.0;            // mean tone-mapped 8-bit value over the pixels and the three channels (0-255)
};

// The region's mean of a linear image; `display` tone-maps each pixel with `exposure` (stops) as
// `lucent render` and `lucent tonemap` do. Images must have the mask's size.
RegionMean region_mean(const ImageRGBA32F& image, const std::vector<std::uint8_t>& mask, float exposure,
                       const ImageRGBA32F* standard_error = nullptr);

}  // namespace lucent::reference
