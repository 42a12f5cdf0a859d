// thickness_grid.cpp: see thickness_grid.h.
#include "geometry/thickness_grid.h"

#include <algorithm>
#include <cmath>

#include "lucent/error.h"

namespace lucent {

ThicknessGrid thickness_grid(const TriangleMesh& world_mesh, const std::vector<double>& per_triangle, double fallback,
                             int cells) {
  const std::size_t triangles = world_mesh.indices.size() / 3;
  if (per_triangle.size() != triangles) throw Error("thickness grid: one thickness per triangle expected");
  if (!(fallback > 0.0) || !std::isfinite(fallback)) throw Error("thickness grid: the fallback thickness must be positive");
  glm::vec3 lower(1e30f), upper(-1e30f);
  for (const glm::vec3& p : world_mesh.positions) lower = glm::min(lower, p), upper = glm::max(upper, p);
  ThicknessGrid grid;
  grid.fallback = static_cast<float>(fallback);
  const float extent = std::max({upper.x - lower.x, upper.y - lower.y, upper.z - lower.z});
  if (!(extent > 0.0f) || !std::isfinite(extent)) return grid;  // nothing to measure: the fallback everywhere
  grid.cell = extent / static_cast<float>(cells);
  grid.origin = lower - glm::vec3(grid.cell);  // one node of margin on every side
  for (int a = 0; a < 3; ++a)
    grid.nodes[a] = static_cast<int>(std::ceil((upper[a] - lower[a]) / grid.cell)) + 3;
  const std::size_t count = static_cast<std::size_t>(grid.nodes.x) * static_cast<std::size_t>(grid.nodes.y) *
                            static_cast<std::size_t>(grid.nodes.z);
  std::vector<double> sum(count, 0.0), weight(count, 0.0);
  auto splat = [&](glm::dvec3 x, double w, double value) {
    const glm::dvec3 p = (x - glm::dvec3(grid.origin)) / static_cast<double>(grid.cell);
    const glm::dvec3 p0 = glm::floor(p);
    const glm::dvec3 t = p - p0;
    const glm::ivec3 i = glm::ivec3(p0);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::ivec3 node = i + glm::ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
      if (glm::any(glm::lessThan(node, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(node, grid.nodes))) continue;
      const double tw = (corner & 1 ? t.x : 1.0 - t.x) * (corner & 2 ? t.y : 1.0 - t.y) * (corner & 4 ? t.z : 1.0 - t.z);
      const std::size_t n = static_cast<std::size_t>(node.x) +
                            static_cast<std::size_t>(grid.nodes.x) *
                                (static_cast<std::size_t>(node.y) + static_cast<std::size_t>(grid.nodes.y) * static_cast<std::size_t>(node.z));
      sum[n] += w * tw * value;
      weight[n] += w * tw;
    }
  };
  for (std::size_t t = 0; t < triangles; ++t) {
    const double value = per_triangle[t];
    if (!(value > 0.0) || !std::isfinite(value)) continue;
    const glm::dvec3 a(world_mesh.positions[world_mesh.indices[3 * t]]);
    const glm::dvec3 b(world_mesh.positions[world_mesh.indices[3 * t + 1]]);
    const glm::dvec3 c(world_mesh.positions[world_mesh.indices[3 * t + 2]]);
    const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
    if (!(area > 0.0)) continue;
    // k^2 sub-triangles of the triangle's edges cut in k, their centroids a quarter of a cell or less apart.
    const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    const int k = std::clamp(static_cast<int>(std::ceil(longest / (0.25 * grid.cell))), 1, 256);
    const double w = area / static_cast<double>(k * k);
    for (int i = 0; i < k; ++i)
      for (int j = 0; i + j < k; ++j) {
        const double u = (i + 1.0 / 3.0) / k, v = (j + 1.0 / 3.0) / k;
        splat(a + u * (b - a) + v * (c - a), w, value);
        if (i + j + 1 < k) splat(a + (u + 1.0 / (3.0 * k)) * (b - a) + (v + 1.0 / (3.0 * k)) * (c - a), w, value);
      }
  }
  grid.values.assign(count, 0.0f);
  for (std::size_t n = 0; n < count; ++n)
    if (weight[n] > 0.0) grid.values[n] = static_cast<float>(sum[n] / weight[n]);
  return grid;
}

float thickness_at(const ThicknessGrid& grid, glm::vec3 x) {
  if (grid.empty()) return grid.fallback;
  const glm::vec4 header0(grid.origin, 1.0f / grid.cell);
  const glm::vec4 header1(glm::vec3(grid.nodes), grid.fallback);
  const shader::ThicknessCell c = shader::thickness_cell(x, header0, header1);
  if (c.node < 0) return grid.fallback;
  auto node = [&](int offset) { return grid.values[static_cast<std::size_t>(c.node + offset)]; };
  const int sx = c.stride.x, sy = c.stride.y, sz = c.stride.z;
  const glm::vec4 lower(node(0), node(sx), node(sy), node(sx + sy));
  const glm::vec4 upper(node(sz), node(sx + sz), node(sy + sz), node(sx + sy + sz));
  return shader::thickness_blend(lower, upper, c.t, grid.fallback);
}

int append_thickness_grid(const ThicknessGrid& grid, std::vector<glm::vec4>& texels) {
  const int first = static_cast<int>(texels.size());
  texels.emplace_back(grid.origin, 1.0f / grid.cell);
  texels.emplace_back(glm::vec3(grid.nodes), grid.fallback);
  for (std::size_t n = 0; n < grid.values.size(); n += 4) {
    glm::vec4 packed(0.0f);
    for (std::size_t k = 0; k < 4 && n + k < grid.values.size(); ++k) packed[static_cast<int>(k)] = grid.values[n + k];
    texels.push_back(packed);
  }
  return first;
}

}  // namespace lucent
