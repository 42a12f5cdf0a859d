// isosurface_grid.h: the sampling grid of an isosurface extraction: a box split into cells, samples at the
// cell corners (grid points).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>

#include <glm/glm.hpp>

#include "geometry/blob_field.h"

namespace lucent::geometry {

struct IsosurfaceGrid {
  glm::ivec3 cells{64};     // cells per axis; points per axis are cells + 1
  glm::vec3 lower{-1.0f};   // box corners [scene units]
  glm::vec3 upper{1.0f};

  glm::vec3 spacing() const { return (upper - lower) / glm::vec3(cells); }  // cell size [scene units]
  glm::ivec3 points() const { return cells + 1; }
  std::size_t point_count() const {
    glm::ivec3 p = points();
    return static_cast<std::size_t>(p.x) * static_cast<std::size_t>(p.y) * static_cast<std::size_t>(p.z);
  }
  std::size_t point_index(glm::ivec3 p) const {
    glm::ivec3 n = points();
    auto size = [](int v) { return static_cast<std::size_t>(v); };
    return size(p.x) + size(n.x) * (size(p.y) + size(n.y) * size(p.z));
  }
};

// The blob scene's grid: the box that always holds the body (shader::blob_body_bound) plus a 0.05-unit margin,
// with `resolution` cells along its longest axis (x) and near-cubic cells (the same count per unit length)
// along the others: resolution 64 gives 64 x 40 x 41 cells.
inline IsosurfaceGrid blob_grid(int resolution) {
  glm::vec3 half = shader::blob_body_bound() + glm::vec3(0.05f);
  float longest = std::max(half.x, std::max(half.y, half.z));
  IsosurfaceGrid grid;
  for (int axis = 0; axis < 3; ++axis) {
    float count = static_cast<float>(resolution) * half[axis] / longest;
    grid.cells[axis] = std::max(2, static_cast<int>(std::lround(count)));
  }
  grid.lower = -half;
  grid.upper = half;
  return grid;
}

}  // namespace lucent::geometry
