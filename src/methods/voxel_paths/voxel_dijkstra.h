// voxel_dijkstra.h: the CPU reference for the voxel-paths GPU solver: Dijkstra's algorithm (as in the paper,
// Section 2.1) on the same graph: a node per inside voxel, edges to its 26 inside neighbours, cost
// 0.5 (sigma_t(u) + sigma_t(v)) |u - v| (sigma_t integrated along the edge by the trapezoid rule; exact for a
// homogeneous object). Each colour band is an independent shortest-path problem with its own costs and sources.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "methods/voxel_paths/voxel_grid.h"

namespace lucent::methods::voxel_paths {

struct VoxelSource {
  std::size_t voxel;   // grid index
  glm::vec3 n0;        // initial optical path length per band (the paper's -ln(F_t P), eq. 2)
};

// Edge lengths in voxel units by the number of axes an edge moves along (1, 2 or 3); the GPU uses the same
// float constants so both sum the same numbers.
inline constexpr float kEdgeLength[4] = {0.0f, 1.0f, 1.4142135f, 1.7320508f};

// Shortest optical path length n(v) per band to every voxel (kUnreached outside and where no source reaches).
// labels: uint per voxel (0 outside); sigma_t: rgb per label [1/scene unit].
std::vector<glm::vec3> dijkstra_optical_paths(const VoxelGrid& grid, std::span<const std::uint32_t> labels,
                                              std::span<const glm::vec4> sigma_t,
                                              std::span<const VoxelSource> sources);
// The same with a coefficient per voxel (heterogeneous media, coefficient_field.h): coefficients: rgb per voxel
// [1/scene unit]; an edge costs 0.5 (c(u) + c(v)) |u - v|, the trapezoid rule for the integral of c along it.
std::vector<glm::vec3> dijkstra_optical_paths_per_voxel(const VoxelGrid& grid, std::span<const std::uint32_t> labels,
                                                        std::span<const glm::vec4> coefficients,
                                                        std::span<const VoxelSource> sources);

}  // namespace lucent::methods::voxel_paths
