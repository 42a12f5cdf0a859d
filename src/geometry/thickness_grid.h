// thickness_grid.h: builds the multipole model's thickness grid of an object (lucent::ThicknessGrid) from the shape
// diameter of each triangle, reads it on the CPU and packs it for the GPU; the lookup itself is shared with the
// shaders (geometry/thickness_field.h).
#pragma once
#include <vector>

#include "geometry/thickness_field.h"
#include "lucent/mesh.h"
#include "lucent/scene.h"

namespace lucent {

// Cells along the longest side of the object's box: 48 keeps the grid under 0.5 MiB (a cube's 51^3 nodes) and
// its spacing a few per cent of the object, finer than the thickness changes on the parts where it matters.
constexpr int kThicknessGridCells = 48;

// The grid of a mesh already in world space (scene units) from one thickness per triangle [scene units; <= 0: none,
// such as a triangle whose rays met nothing]: each triangle spreads its value over the nodes around it (trilinear
// weights times area, over points a quarter of a cell or less apart on the triangle), and a node holds the
// weighted mean of what reached it. `fallback` [scene units] > 0.
ThicknessGrid thickness_grid(const TriangleMesh& world_mesh, const std::vector<double>& per_triangle, double fallback,
                             int cells = kThicknessGridCells);

// The thickness at x [scene units] (as the shaders read it).
float thickness_at(const ThicknessGrid& grid, glm::vec3 x);

// Appends the grid to the GPU buffer's texels in the layout of geometry/thickness_field.h; returns the index of its first texel.
int append_thickness_grid(const ThicknessGrid& grid, std::vector<glm::vec4>& texels);

}  // namespace lucent
