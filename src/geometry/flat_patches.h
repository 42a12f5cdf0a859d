// flat_patches.h: the flat faces of a mesh: maximal connected sets of flat-shaded triangles (every corner normal the
// triangle's plane normal) in one plane. A faceted object (a box, a slab, a cut stone) carries light into a medium
// through each face that faces the light, each face with its own refracted direction, so a point inside receives
// light through several of them; the specular-chain solvers seed one chain per large face (reference/
// boundary_light.h, the walk's boundary_light.glsl).
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

struct FlatPatch {
  glm::vec3 normal{0.0f};  // unit, on the side of the corner normals
  float area = 0.0f;
};

struct FlatPatches {
  std::vector<FlatPatch> patches;    // the largest first
  std::vector<std::int32_t> patch_of;  // per triangle: its patch, or -1 (smooth-shaded, or a face too small)
};

// Faces of at least `min_area_fraction` of the mesh's area, at most `max_patches` of them. `neighbours`: per
// triangle its neighbours across edges (geometry/triangle_adjacency.h).
FlatPatches flat_patches(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                         std::span<const glm::vec3> normals, std::span<const std::array<std::int32_t, 3>> neighbours,
                         float min_area_fraction = 0.01f, int max_patches = 16);

}  // namespace lucent
