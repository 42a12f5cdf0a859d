// flat_patches.cpp: see flat_patches.h.
#include "geometry/flat_patches.h"

#include <algorithm>
#include <cmath>

namespace lucent {
namespace {

constexpr double kSameDirection = 1e-5;  // unit normals closer than this are one direction

// The triangle's plane normal when its three corner normals are that normal (flat shading); zero otherwise.
glm::dvec3 flat_normal(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                       std::span<const glm::vec3> normals, std::size_t t) {
  const glm::dvec3 a(positions[indices[3 * t]]), b(positions[indices[3 * t + 1]]), c(positions[indices[3 * t + 2]]);
  glm::dvec3 n = glm::cross(b - a, c - a);
  const double length = glm::length(n);
  if (!(length > 0.0)) return glm::dvec3(0.0);
  n /= length;
  glm::dvec3 corner(normals[indices[3 * t]]);
  if (glm::dot(n, corner) < 0.0) n = -n;
  for (int k = 0; k < 3; ++k)
    if (glm::length(glm::dvec3(normals[indices[3 * t + static_cast<std::size_t>(k)]]) - n) > kSameDirection)
      return glm::dvec3(0.0);
  return n;
}

double area(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices, std::size_t t) {
  const glm::dvec3 a(positions[indices[3 * t]]), b(positions[indices[3 * t + 1]]), c(positions[indices[3 * t + 2]]);
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

}  // namespace

FlatPatches flat_patches(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                         std::span<const glm::vec3> normals, std::span<const std::array<std::int32_t, 3>> neighbours,
                         float min_area_fraction, int max_patches) {
  const std::size_t triangles = indices.size() / 3;
  std::vector<glm::dvec3> flat(triangles);
  double total = 0.0;
  for (std::size_t t = 0; t < triangles; ++t) {
    flat[t] = flat_normal(positions, indices, normals, t);
    total += area(positions, indices, t);
  }
  // Flood fill over neighbours with the same flat normal.
  std::vector<std::int32_t> component(triangles, -1);
  struct Candidate {
    glm::dvec3 normal;
    double area;
    std::int32_t id;
  };
  std::vector<Candidate> candidates;
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < triangles; ++seed) {
    if (component[seed] >= 0 || flat[seed] == glm::dvec3(0.0)) continue;
    const auto id = static_cast<std::int32_t>(candidates.size());
    candidates.push_back({flat[seed], 0.0, id});
    component[seed] = id;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::size_t t = stack.back();
      stack.pop_back();
      candidates.back().area += area(positions, indices, t);
      for (std::int32_t n : neighbours[t]) {
        if (n < 0 || component[static_cast<std::size_t>(n)] >= 0) continue;
        if (glm::length(flat[static_cast<std::size_t>(n)] - flat[seed]) > kSameDirection) continue;
        component[static_cast<std::size_t>(n)] = id;
        stack.push_back(static_cast<std::size_t>(n));
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.area > b.area; });
  FlatPatches out;
  std::vector<std::int32_t> kept(candidates.size(), -1);
  for (const Candidate& c : candidates) {
    if (static_cast<int>(out.patches.size()) >= max_patches || c.area < min_area_fraction * total) break;
    kept[static_cast<std::size_t>(c.id)] = static_cast<std::int32_t>(out.patches.size());
    out.patches.push_back({glm::vec3(c.normal), static_cast<float>(c.area)});
  }
  out.patch_of.resize(triangles, -1);
  for (std::size_t t = 0; t < triangles; ++t)
    if (component[t] >= 0) out.patch_of[t] = kept[static_cast<std::size_t>(component[t])];
  return out;
}

}  // namespace lucent
