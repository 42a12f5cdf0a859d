// walk_boundary.cpp: see walk_boundary.h.
#include "methods/random_walk/walk_boundary.h"

#include <bit>
#include <cstdint>

#include "geometry/flat_patches.h"
#include "geometry/triangle_adjacency.h"
#include "methods/random_walk/triangle_bvh.h"
#include "lucent/mesh.h"

namespace lucent::methods::random_walk {
namespace {

float area(const shader::TriangleGPU& t) { return 0.5f * glm::length(glm::cross(glm::vec3(t.e1), glm::vec3(t.e2))); }

}  // namespace

WalkBoundary build_walk_boundary(const Scene& scene, std::span<const shader::TriangleGPU> triangles) {
  WalkBoundary boundary;
  // Where each gathered triangle went in the BVH's order.
  std::vector<std::int32_t> position_of(triangles.size(), -1);
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    const std::uint32_t original = triangle_original_index(triangles[k]);
    if (original < position_of.size()) position_of[original] = static_cast<std::int32_t>(k);
  }
  boundary.neighbours.assign(triangles.size(), glm::ivec4(-1, -1, -1, -1));
  boundary.ranges.assign(scene.objects.size(), glm::ivec2(0));
  boundary.face_ranges.assign(scene.objects.size(), glm::ivec2(0));
  // The gathered order: each mesh object's triangles in its index order (gather_scene_triangles).
  std::size_t first = 0;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    if (object.blob_resolution > 0) continue;
    const std::size_t count = object.mesh.indices.size() / 3;
    if (object.translucent()) {
      const TriangleMesh world = transformed(object.mesh, object.world_from_object);
      const auto local = triangle_neighbours(world.positions, world.indices);
      const FlatPatches faces = flat_patches(world.positions, world.indices, world.normals, local);
      const int first_face = static_cast<int>(boundary.faces.size());
      boundary.face_ranges[i] = glm::ivec2(first_face, static_cast<int>(faces.patches.size()));
      for (const FlatPatch& face : faces.patches) boundary.faces.emplace_back(face.normal, 0.0f);
      for (std::size_t t = 0; t < count && first + t < position_of.size(); ++t) {
        const std::int32_t k = position_of[first + t];
        if (k < 0) continue;
        for (int e = 0; e < 3; ++e) {
          const std::int32_t n = local[t][static_cast<std::size_t>(e)];
          boundary.neighbours[static_cast<std::size_t>(k)][e] =
              n < 0 ? -1 : position_of[first + static_cast<std::size_t>(n)];
        }
        boundary.neighbours[static_cast<std::size_t>(k)].w = faces.patch_of[t] < 0 ? -1 : first_face + faces.patch_of[t];
      }
      boundary.ranges[i] = glm::ivec2(static_cast<int>(boundary.areas.size()), static_cast<int>(count));
      for (std::size_t t = 0; t < count && first + t < position_of.size(); ++t)
        boundary.areas.emplace_back(0.0f, std::bit_cast<float>(position_of[first + t]));
    }
    first += count;
  }
  update_walk_areas(boundary, triangles);
  return boundary;
}

void update_walk_areas(WalkBoundary& boundary, std::span<const shader::TriangleGPU> triangles) {
  for (const glm::ivec2 range : boundary.ranges) {
    if (range.y == 0) continue;
    double total = 0.0;
    for (int i = 0; i < range.y; ++i) {
      glm::vec2& entry = boundary.areas[static_cast<std::size_t>(range.x + i)];
      total += area(triangles[static_cast<std::size_t>(std::bit_cast<std::int32_t>(entry.y))]);
      entry.x = static_cast<float>(total);
    }
    for (int i = 0; i < range.y; ++i) {
      glm::vec2& entry = boundary.areas[static_cast<std::size_t>(range.x + i)];
      entry.x = total > 0.0 ? static_cast<float>(entry.x / total) : static_cast<float>(i + 1) / static_cast<float>(range.y);
    }
    boundary.areas[static_cast<std::size_t>(range.x + range.y - 1)].x = 1.0f;
  }
}

}  // namespace lucent::methods::random_walk
