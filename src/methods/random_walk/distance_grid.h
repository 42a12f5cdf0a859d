// distance_grid.h: the random-walk method's distance grid: a regular grid of cubic cells over a box (the
// translucent objects' bounds plus a margin), each cell centre holding the exact distance to the nearest triangle.
// The distance to a surface is 1-Lipschitz, so D(c) - |x - c| is a lower bound of the distance at any point x,
// for any cell centre c; lower_bound_distance uses the nearest centre, as the shaders do on the uploaded 3D
// texture (R32F, texel (i, j, k) = distances[i + cells.x * (j + cells.y * k)]).
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "methods/random_walk/triangle_bvh.h"

namespace lucent::methods::random_walk {

struct DistanceGridOptions {
  int max_cells_per_axis = 64;  // along the box's longest axis; the others get as many cells as cover them
  float margin = 0.05f;         // added on every side, as a fraction of the box's longest side
  int threads = 0;              // filling the grid (the same result with any number); 0: one per hardware thread
};

struct DistanceGrid {
  glm::ivec3 cells{0};                 // per axis
  glm::vec3 origin{0.0f};              // the lower corner of cell (0, 0, 0) [scene units]
  float cell_size = 0.0f;              // edge of the cubic cells [scene units]
  std::vector<float> distances;        // at the cell centres, x fastest [scene units]

  // The centre of cell (i, j, k).
  glm::vec3 cell_centre(glm::ivec3 cell) const { return origin + (glm::vec3(cell) + 0.5f) * cell_size; }
  // D(c) - |p - c|, at least 0, with c the centre of the cell containing p (of the nearest cell when p is
  // outside the grid): never more than the distance from p to the nearest triangle, and within one cell
  // diagonal of it inside the grid. 0 for an empty grid.
  float lower_bound_distance(glm::vec3 p) const;
};

// The grid over [lower, upper] plus the margin, filled with the BVH's exact distances. An empty box (lower >
// upper) or an empty BVH gives an empty grid.
DistanceGrid build_distance_grid(const TriangleBvh& bvh, glm::vec3 lower, glm::vec3 upper,
                                 const DistanceGridOptions& options = {});

}  // namespace lucent::methods::random_walk
