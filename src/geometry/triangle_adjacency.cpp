// triangle_adjacency.cpp: see triangle_adjacency.h.
#include "geometry/triangle_adjacency.h"

#include <algorithm>
#include <cstring>
#include <unordered_map>

namespace lucent {
namespace {

// An edge as its two corners' positions, the smaller (lexicographically) first.
struct EdgeKey {
  std::array<float, 6> corners;
  bool operator==(const EdgeKey& other) const { return corners == other.corners; }
};

struct EdgeKeyHash {
  std::size_t operator()(const EdgeKey& key) const {
    std::size_t h = 1469598103934665603ULL;
    for (float f : key.corners) {
      std::uint32_t bits;
      std::memcpy(&bits, &f, sizeof bits);
      h = (h ^ bits) * 1099511628211ULL;
    }
    return h;
  }
};

bool less(const glm::vec3& a, const glm::vec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

EdgeKey edge_key(glm::vec3 a, glm::vec3 b) {
  if (less(b, a)) std::swap(a, b);
  return {{a.x, a.y, a.z, b.x, b.y, b.z}};
}

}  // namespace

std::vector<std::array<std::int32_t, 3>> triangle_neighbours(std::span<const glm::vec3> positions,
                                                             std::span<const std::uint32_t> indices) {
  const std::size_t triangles = indices.size() / 3;
  std::vector<std::array<std::int32_t, 3>> neighbours(triangles, {-1, -1, -1});
  // The first triangle seen on each edge, and how many share it.
  struct Seen {
    std::int32_t triangle, edge;          // the first triangle on the edge
    std::int32_t second_triangle, second_edge;
    int count;
  };
  std::unordered_map<EdgeKey, Seen, EdgeKeyHash> edges;
  edges.reserve(triangles * 3 / 2 + 1);
  for (std::size_t t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 a = positions[indices[3 * t + static_cast<std::size_t>(k)]];
      const glm::vec3 b = positions[indices[3 * t + static_cast<std::size_t>((k + 1) % 3)]];
      auto [it, inserted] = edges.try_emplace(edge_key(a, b), Seen{static_cast<std::int32_t>(t), k, -1, -1, 0});
      Seen& seen = it->second;
      ++seen.count;
      if (inserted) continue;
      auto& first = neighbours[static_cast<std::size_t>(seen.triangle)][static_cast<std::size_t>(seen.edge)];
      if (seen.count == 2) {
        first = static_cast<std::int32_t>(t);
        neighbours[t][static_cast<std::size_t>(k)] = seen.triangle;
        seen.second_triangle = static_cast<std::int32_t>(t), seen.second_edge = k;
      } else {  // a third triangle on the edge: no walking across it from either of the first two
        first = -1;
        neighbours[static_cast<std::size_t>(seen.second_triangle)][static_cast<std::size_t>(seen.second_edge)] = -1;
      }
    }
  return neighbours;
}

}  // namespace lucent
