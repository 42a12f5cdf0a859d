// charts.h: segmentation of a mesh into charts by normal deviation and their orthographic projection (after Lensch
// et al. 2002, Section 5.1; see atlas.h for the rules).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace lucent::texture_space {

struct Chart {
  std::vector<std::uint32_t> triangles;  // into the mesh's triangles
  glm::dvec3 normal{0.0, 0.0, 1.0};      // unit axis of the cone enclosing the triangles' normals (every normal
                                         // within the cone's half-angle of it): the projection direction
};

// Charts covering every triangle once. `positions` are world space [scene units]; triangles are adjacent when
// they share an edge between the same two positions (exact equality) and no third triangle shares it.
std::vector<Chart> grow_charts(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices,
                               float cone_deg);

// Orthographic projection onto the plane of `normal`, in a right-handed frame (tangent, bitangent, normal), so
// triangles facing along `normal` keep counter-clockwise order [scene units].
glm::dvec2 project(glm::dvec3 p, glm::dvec3 normal);

// Whether two of the projected triangles (three points each, consecutive) overlap by more than `tolerance`.
bool projected_triangles_overlap(const std::vector<glm::dvec2>& corners, double tolerance);

}  // namespace lucent::texture_space
