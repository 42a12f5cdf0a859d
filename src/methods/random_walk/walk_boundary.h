// walk_boundary.h: what the walk's specular-chain solvers (shaders/boundary_light.glsl) read of the translucent
// objects' surfaces beside the triangles: each triangle's neighbours across its edges (the solvers walk across
// them), and each translucent object's triangles by area (their random seeds are uniform over its surface).
#pragma once
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/scene.h"
#include "methods/random_walk/random_walk_io.h"

namespace lucent::methods::random_walk {

struct WalkBoundary {
  // Per triangle of the BVH's order (TriangleGPU[]): xyz the triangles across edges 0-1, 1-2, 2-0 of the same
  // object, -1 where none; w its large flat face (below), -1 where none (LUCENT_BINDING_WALK_NEIGHBOURS).
  std::vector<glm::ivec4> neighbours;
  // Per translucent object, its triangles: x the cumulative fraction of its area, y the triangle's index in the
  // BVH's order (float bits) (LUCENT_BINDING_WALK_AREAS); `ranges[object]`: its first entry and count (0 0 for the
  // others).
  std::vector<glm::vec2> areas;
  std::vector<glm::ivec2> ranges;
  // The translucent objects' large flat faces (geometry/flat_patches.h): xyz the unit normal
  // (LUCENT_BINDING_WALK_FACES); `face_ranges[object]`: its first and count; a triangle's face index into `faces` in
  // its `neighbours` entry's w (-1: none).
  std::vector<glm::vec4> faces;
  std::vector<glm::ivec2> face_ranges;
};

// `triangles`: the BVH's (TriangleGPU::n0.w holds each one's index in the gathered order, object by object as
// gather_scene_triangles lists them).
WalkBoundary build_walk_boundary(const Scene& scene, std::span<const shader::TriangleGPU> triangles);

// The area distribution again after the triangles moved (deforming meshes; the neighbours stay).
void update_walk_areas(WalkBoundary& boundary, std::span<const shader::TriangleGPU> triangles);

}  // namespace lucent::methods::random_walk
