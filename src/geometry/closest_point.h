// closest_point.h: the points of a segment and of a triangle nearest to a point, in double precision. Used by the
// references' distance queries (reference/embree_scene.h) and by the scene loader's checks of where lights lie.
#pragma once
#include <glm/glm.hpp>

#include "lucent/mesh.h"

namespace lucent {

// The point of segment [a, b] nearest to p (a when the segment is a point).
glm::dvec3 closest_point_on_segment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b);

// The point of triangle (a, b, c) nearest to p (a degenerate triangle: the nearest point of its edges).
glm::dvec3 closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c);

// The distance from p to the nearest triangle of `mesh` (both in the same space), by visiting every triangle; a
// mesh without triangles is infinitely far.
double distance_to_mesh(const TriangleMesh& mesh, const glm::dvec3& p);

}  // namespace lucent
