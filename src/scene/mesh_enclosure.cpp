// mesh_enclosure.cpp: see mesh_enclosure.h.
#include "scene/mesh_enclosure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace lucent {
namespace {

using Position = std::array<float, 3>;

Position key(const glm::vec3& p) { return {p.x, p.y, p.z}; }

}  // namespace

std::size_t open_edge_count(const TriangleMesh& mesh) {
  std::map<std::pair<Position, Position>, int> uses;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    for (std::size_t k = 0; k < 3; ++k) {
      Position a = key(mesh.positions[mesh.indices[t + k]]), b = key(mesh.positions[mesh.indices[t + (k + 1) % 3]]);
      if (a == b) continue;
      if (b < a) std::swap(a, b);
      ++uses[{a, b}];
    }
  return static_cast<std::size_t>(std::count_if(uses.begin(), uses.end(), [](const auto& e) { return e.second == 1; }));
}

bool encloses(const TriangleMesh& mesh, const glm::dvec3& p) {
  // A direction no mesh is likely to align an edge or a face with.
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.5431, 0.6172, 0.5693));
  int crossings = 0;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
        c(mesh.positions[mesh.indices[t + 2]]);
    // Moeller-Trumbore.
    const glm::dvec3 e1 = b - a, e2 = c - a, q = glm::cross(d, e2);
    const double det = glm::dot(e1, q);
    if (std::abs(det) < 1e-300) continue;
    const glm::dvec3 s = p - a;
    const double u = glm::dot(s, q) / det;
    if (u < 0.0 || u > 1.0) continue;
    const glm::dvec3 r = glm::cross(s, e1);
    const double v = glm::dot(d, r) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    if (glm::dot(e2, r) / det > 0.0) ++crossings;
  }
  return crossings % 2 == 1;
}

}  // namespace lucent
