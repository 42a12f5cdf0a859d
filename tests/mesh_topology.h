// mesh_topology.h: closed-mesh checks shared by the CPU and GL tests: welding by exact position, edge use and
// orientation, Euler characteristic, connected components, signed volume, triangle areas.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/mesh.h"

namespace lucent::test {

inline std::size_t triangle_count(const TriangleMesh& m) { return m.indices.size() / 3; }

struct MeshTopology {
  std::size_t vertices = 0;          // after welding by exact position
  std::size_t edges = 0;             // undirected
  std::size_t triangles = 0;
  std::size_t open_edges = 0;        // used by other than exactly two triangles
  std::size_t misoriented_edges = 0; // used twice in the same direction
  std::size_t components = 0;        // connected through shared welded vertices
  long euler() const { return static_cast<long>(vertices) - static_cast<long>(edges) + static_cast<long>(triangles); }
};

// Welded vertex id of each mesh vertex: vertices with bitwise-equal positions (as floats) share an id.
inline std::vector<std::uint32_t> weld_by_position(const TriangleMesh& mesh, std::size_t* welded_count) {
  std::map<std::array<float, 3>, std::uint32_t> ids;
  std::vector<std::uint32_t> weld(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    glm::vec3 p = mesh.positions[v];
    auto [it, inserted] = ids.emplace(std::array<float, 3>{p.x, p.y, p.z}, static_cast<std::uint32_t>(ids.size()));
    weld[v] = it->second;
  }
  *welded_count = ids.size();
  return weld;
}

inline MeshTopology analyze_topology(const TriangleMesh& mesh) {
  MeshTopology t;
  std::vector<std::uint32_t> weld = weld_by_position(mesh, &t.vertices);
  t.triangles = mesh.indices.size() / 3;
  // Per undirected edge: (uses, uses in the direction lower id -> higher id).
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<int, int>> edges;
  std::vector<std::uint32_t> parent(t.vertices);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (std::size_t f = 0; f < t.triangles; ++f)
    for (int k = 0; k < 3; ++k) {
      std::uint32_t a = weld[mesh.indices[3 * f + k]], b = weld[mesh.indices[3 * f + (k + 1) % 3]];
      auto& use = edges[{std::min(a, b), std::max(a, b)}];
      use.first += 1;
      use.second += a < b ? 1 : 0;
      parent[find(a)] = find(b);
    }
  t.edges = edges.size();
  for (const auto& [key, use] : edges) {
    if (use.first != 2) ++t.open_edges;
    else if (use.second != 1) ++t.misoriented_edges;
  }
  std::vector<bool> used(t.vertices, false);
  for (std::uint32_t index : mesh.indices) used[weld[index]] = true;
  for (std::uint32_t v = 0; v < t.vertices; ++v)
    if (used[v] && find(v) == v) ++t.components;
  return t;
}

inline glm::dvec3 corner(const TriangleMesh& mesh, std::size_t f, int k) {
  return glm::dvec3(mesh.positions[mesh.indices[3 * f + static_cast<std::size_t>(k)]]);
}

// (v1 - v0) x (v2 - v0): the counter-clockwise normal, length twice the area.
inline glm::dvec3 face_normal(const TriangleMesh& mesh, std::size_t f) {
  return glm::cross(corner(mesh, f, 1) - corner(mesh, f, 0), corner(mesh, f, 2) - corner(mesh, f, 0));
}

// Enclosed volume by the divergence theorem: positive when the faces are counter-clockwise from outside.
inline double signed_volume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (std::size_t f = 0; f < mesh.indices.size() / 3; ++f)
    volume += glm::dot(corner(mesh, f, 0), glm::cross(corner(mesh, f, 1), corner(mesh, f, 2))) / 6.0;
  return volume;
}

}  // namespace lucent::test
