// voxel_dijkstra.cpp: see voxel_dijkstra.h.
#include "methods/voxel_paths/voxel_dijkstra.h"

#include <cstdlib>
#include <functional>
#include <queue>
#include <utility>

namespace lucent::methods::voxel_paths {
namespace {

// One band: binary-heap Dijkstra with lazy deletion.
void dijkstra_band(const VoxelGrid& grid, std::span<const std::uint32_t> labels,
                   std::span<const glm::vec4> coefficients, std::span<const VoxelSource> sources, int band,
                   std::vector<glm::vec3>& n) {
  using Entry = std::pair<float, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (const VoxelSource& source : sources) {
    if (labels[source.voxel] == 0 || source.n0[band] >= n[source.voxel][band]) continue;
    n[source.voxel][band] = source.n0[band];
    queue.emplace(source.n0[band], source.voxel);
  }
  const int r = grid.resolution;
  while (!queue.empty()) {
    auto [d, index] = queue.top();
    queue.pop();
    if (d > n[index][band]) continue;  // stale entry
    glm::ivec3 v = grid.voxel(index);
    float sigma_v = coefficients[index][band];
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          glm::ivec3 u = v + glm::ivec3(dx, dy, dz);
          if (u == v || glm::any(glm::lessThan(u, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(u, glm::ivec3(r))))
            continue;
          std::size_t neighbour = grid.index(u);
          if (labels[neighbour] == 0) continue;
          float edge = grid.voxel_size * kEdgeLength[std::abs(dx) + std::abs(dy) + std::abs(dz)];
          float candidate = d + 0.5f * (sigma_v + coefficients[neighbour][band]) * edge;
          if (candidate < n[neighbour][band]) {
            n[neighbour][band] = candidate;
            queue.emplace(candidate, neighbour);
          }
        }
  }
}

}  // namespace

std::vector<glm::vec3> dijkstra_optical_paths(const VoxelGrid& grid, std::span<const std::uint32_t> labels,
                                              std::span<const glm::vec4> sigma_t,
                                              std::span<const VoxelSource> sources) {
  std::vector<glm::vec4> coefficients(labels.size());
  for (std::size_t i = 0; i < labels.size(); ++i) coefficients[i] = sigma_t[labels[i]];
  return dijkstra_optical_paths_per_voxel(grid, labels, coefficients, sources);
}

std::vector<glm::vec3> dijkstra_optical_paths_per_voxel(const VoxelGrid& grid, std::span<const std::uint32_t> labels,
                                                        std::span<const glm::vec4> coefficients,
                                                        std::span<const VoxelSource> sources) {
  std::vector<glm::vec3> n(grid.voxel_count(), glm::vec3(kUnreached));
  for (int band = 0; band < 3; ++band) dijkstra_band(grid, labels, coefficients, sources, band, n);
  return n;
}

}  // namespace lucent::methods::voxel_paths
