// dilate.h: gutters around the charts of an atlas texture (CPU).
#pragma once
#include <vector>

#include <glm/glm.hpp>

namespace lucent::texture_space {

// Fills each empty texel (w == 0) that has a filled neighbour with that neighbour's value (4-neighbours first, then
// diagonals, in a fixed order), `texels` times over: gutters so that bilinear lookups and filters near chart
// borders read surface values. Dilate textures that are looked up (irradiance), not the G-buffer's area ratio:
// gutter texels carry no surface area (Chang et al. 2008, Eq. 7). `values` holds size x size texels.
void dilate(std::vector<glm::vec4>& values, int size, int texels);

}  // namespace lucent::texture_space
