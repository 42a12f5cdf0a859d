// closest_point.cpp: see closest_point.h.
#include "geometry/closest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lucent {

glm::dvec3 closest_point_on_segment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double length2 = glm::dot(ab, ab);
  if (!(length2 > 0.0)) return a;
  return a + std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) * ab;
}

glm::dvec3 closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, normal = glm::cross(ab, ac);
  const double area2 = glm::dot(normal, normal);
  if (area2 > 0.0) {
    const glm::dvec3 foot = p - glm::dot(p - a, normal) / area2 * normal;
    // Barycentric coordinates of the foot from the signed areas of the sub-triangles opposite each corner.
    const double wb = glm::dot(glm::cross(foot - a, ac), normal) / area2;
    const double wc = glm::dot(glm::cross(ab, foot - a), normal) / area2;
    if (wb >= 0.0 && wc >= 0.0 && wb + wc <= 1.0) return foot;
  }
  const glm::dvec3 candidates[3] = {closest_point_on_segment(p, a, b), closest_point_on_segment(p, b, c),
                                    closest_point_on_segment(p, c, a)};
  glm::dvec3 best = candidates[0];
  for (const glm::dvec3& q : candidates)
    if (glm::dot(q - p, q - p) < glm::dot(best - p, best - p)) best = q;
  return best;
}

double distance_to_mesh(const TriangleMesh& mesh, const glm::dvec3& p) {
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
        c(mesh.positions[mesh.indices[t + 2]]);
    nearest = std::min(nearest, glm::length(closest_point_on_triangle(p, a, b, c) - p));
  }
  return nearest;
}

}  // namespace lucent
