// sheet_solid.cpp: see sheet_solid.h.
#include "geometry/sheet_solid.h"

#include <array>
#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "geometry/position_bits.h"
#include "lucent/error.h"

namespace lucent {

TriangleMesh sheet_solid(const TriangleMesh& mesh, float thickness) {
  if (!(thickness > 0.0f) || !std::isfinite(thickness))
    throw Error(fmt::format("sheet thickness {} is not a positive number", thickness));
  const std::size_t vertices = mesh.positions.size();
  const bool has_uvs = mesh.uvs.size() == vertices;

  // Positions welded by their exact bits: vertices split along seams share one offset direction and one border.
  std::map<std::array<std::uint32_t, 3>, std::uint32_t> index_of;
  std::vector<std::uint32_t> welded(vertices);
  for (std::size_t v = 0; v < vertices; ++v)
    welded[v] = index_of.emplace(position_bits(mesh.positions[v]), static_cast<std::uint32_t>(index_of.size())).first->second;

  // Area-weighted face normals (the cross product's length is twice the area) summed per welded position, and the
  // welded edges' use: +1 for a->b, -1 for b->a; an edge used once in one direction is a border.
  std::vector<glm::dvec3> normal_sum(index_of.size(), glm::dvec3(0.0));
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_use;
  bool any_area = false;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::array<std::uint32_t, 3> c{mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    const glm::dvec3 a(mesh.positions[c[0]]), b(mesh.positions[c[1]]), d(mesh.positions[c[2]]);
    const glm::dvec3 n = glm::cross(b - a, d - a);
    if (glm::length(n) > 0.0) any_area = true;
    for (int k = 0; k < 3; ++k) {
      normal_sum[welded[c[static_cast<std::size_t>(k)]]] += n;
      const std::uint32_t from = welded[c[static_cast<std::size_t>(k)]], to = welded[c[static_cast<std::size_t>((k + 1) % 3)]];
      if (from < to) ++edge_use[{from, to}];
      else --edge_use[{to, from}];
    }
  }
  if (!any_area) throw Error("a sheet needs a triangle with an area");

  TriangleMesh out;
  out.positions = mesh.positions;
  out.normals = mesh.normals;
  if (has_uvs) out.uvs = mesh.uvs;
  out.indices = mesh.indices;
  // The back face: every vertex moved `thickness` against its position's normal, facing the other way.
  const auto back = static_cast<std::uint32_t>(vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    const glm::dvec3 sum = normal_sum[welded[v]];
    const glm::vec3 n = glm::length(sum) > 0.0 ? glm::vec3(glm::normalize(sum)) : glm::vec3(0.0f);
    out.positions.push_back(mesh.positions[v] - thickness * n);
    out.normals.push_back(-n);
    if (has_uvs) out.uvs.push_back(mesh.uvs[v]);
  }
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    for (const std::size_t k : {std::size_t{0}, std::size_t{2}, std::size_t{1}}) out.indices.push_back(back + mesh.indices[t + k]);

  // Walls along the border: for a border edge a->b of a front triangle, the quad a, b, b', a' with its normal
  // (b - a) x n pointing away from the triangle: triangles (a, a', b) and (b, a', b').
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = mesh.indices[t + static_cast<std::size_t>(k)], b = mesh.indices[t + static_cast<std::size_t>((k + 1) % 3)];
      const std::uint32_t wa = welded[a], wb = welded[b];
      if (wa == wb) continue;
      const int use = wa < wb ? edge_use[{wa, wb}] : -edge_use[{wb, wa}];
      if (use != 1) continue;
      const glm::vec3 pa = mesh.positions[a], pb = mesh.positions[b];
      const glm::vec3 pa_back = out.positions[back + a], pb_back = out.positions[back + b];
      glm::vec3 wall = glm::cross(pb - pa, pa - pa_back);
      wall = glm::length(wall) > 0.0f ? glm::normalize(wall) : glm::vec3(0.0f);
      const auto first = static_cast<std::uint32_t>(out.positions.size());
      for (const glm::vec3& p : {pa, pb, pa_back, pb_back}) {
        out.positions.push_back(p);
        out.normals.push_back(wall);
      }
      if (has_uvs)
        for (const std::uint32_t v : {a, b, a, b}) out.uvs.push_back(mesh.uvs[v]);
      for (const std::uint32_t i : {0u, 2u, 1u, 1u, 2u, 3u}) out.indices.push_back(first + i);
    }
  return out;
}

}  // namespace lucent
