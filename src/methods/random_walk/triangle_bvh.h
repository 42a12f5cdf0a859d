// triangle_bvh.h: the random-walk method's CPU geometry: the scene's world-space triangles, a bounding volume
// hierarchy over them built with the binned surface area heuristic and flattened depth-first into the GPU layout
// of random_walk_io.h, its refit after the triangles moved, and CPU queries (closest ray hit, exact distance to
// the nearest triangle) for the tests and for the distance grid (distance_grid.h).
#pragma once
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/scene.h"
#include "methods/random_walk/random_walk_io.h"

namespace lucent::methods::random_walk {

using shader::BvhNodeGPU;
using shader::TriangleGPU;

// The world-space triangles of a scene at one time, in object order, each object's in its index order.
struct SceneTriangles {
  std::vector<TriangleGPU> triangles;  // n0.w: the index in this vector (float bits)
  int skipped_blobs = 0;               // blob objects (isosurfaces, extracted on the GPU): not included
  // The world-space box of the translucent objects' triangles (of all triangles when no mesh is translucent;
  // lower > upper when there are none).
  glm::vec3 translucent_lower{std::numeric_limits<float>::max()};
  glm::vec3 translucent_upper{std::numeric_limits<float>::lowest()};
};

// Every mesh object (or only the translucent ones) at time `seconds`: deformations applied, then the object's
// transform, as the GPU upload does (deformed_mesh, transformed).
SceneTriangles gather_scene_triangles(const Scene& scene, double seconds = 0.0, bool translucent_only = false);

// One triangle in the GPU layout: corners a, b, c, their shading normals, its object and original index.
TriangleGPU make_triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 na, glm::vec3 nb, glm::vec3 nc,
                          std::uint32_t object, std::uint32_t original_index);

// The integers stored as float bits in the GPU structs.
std::uint32_t triangle_object(const TriangleGPU& triangle);
std::uint32_t triangle_original_index(const TriangleGPU& triangle);
std::uint32_t node_offset(const BvhNodeGPU& node);  // leaf: first triangle; interior: right child
std::uint32_t node_count(const BvhNodeGPU& node);   // triangles; 0: interior node

// Moller-Trumbore: the distance t in (0, t_max) along `dir` (not necessarily unit) at which the ray hits the
// triangle (either side), with the barycentrics of corners 1 and 2; nothing when it misses.
struct TriangleHit {
  float t;
  float u, v;
};
std::optional<TriangleHit> intersect_triangle(const TriangleGPU& triangle, glm::vec3 origin, glm::vec3 dir,
                                              float t_max);
// The point of the triangle nearest to p.
glm::vec3 closest_point_on_triangle(const TriangleGPU& triangle, glm::vec3 p);

struct BvhBuildOptions {
  int bins = 16;               // SAH candidate planes per node: bins - 1, along the widest centroid axis
  int leaf_triangles = 4;      // a node of this many triangles or fewer is always a leaf
  int max_leaf_triangles = 8;  // up to this many, a leaf where the SAH finds no cheaper split
  int max_depth = 64;          // a node this deep is a leaf, whatever its size
};

struct BvhHit {
  float t;
  float u, v;              // barycentrics of corners 1 and 2
  std::uint32_t triangle;  // index into TriangleBvh::triangles
};

struct NearestTriangle {
  float distance;
  std::uint32_t triangle;  // index into TriangleBvh::triangles
};

inline constexpr std::uint32_t kNoTriangle = std::numeric_limits<std::uint32_t>::max();

struct TriangleBvh {
  std::vector<BvhNodeGPU> nodes;        // depth-first; nodes[0] the root; empty when there are no triangles
  std::vector<TriangleGPU> triangles;   // the input, reordered so that each leaf's triangles are contiguous
  int depth = 0;                        // of the deepest leaf (the root: 0)

  // Recomputes every node's box bottom-up from `triangles`, after their corners moved (same topology).
  void refit();
  // Replaces the triangles by `moved`, given in the original order (TriangleGPU::n0.w), then refits.
  void refit(std::span<const TriangleGPU> moved);

  // The nearest hit in (0, t_max) along the ray; `dir` need not be unit (t is in units of |dir|).
  std::optional<BvhHit> closest_hit(glm::vec3 origin, glm::vec3 dir, float t_max) const;
  // The exact unsigned distance from p to the nearest triangle when it is below `max_distance`; else
  // `max_distance`.
  float distance_to_nearest(glm::vec3 p, float max_distance = std::numeric_limits<float>::infinity()) const;
  // The same with the triangle (index into `triangles`); nothing when none is closer than `max_distance`.
  // `guess`, a triangle likely to be the nearest (a neighbouring point's), only speeds the search up: its
  // distance is the first search radius.
  std::optional<NearestTriangle> nearest_triangle(glm::vec3 p,
                                                  float max_distance = std::numeric_limits<float>::infinity(),
                                                  std::uint32_t guess = kNoTriangle) const;
};

TriangleBvh build_triangle_bvh(std::span<const TriangleGPU> triangles, const BvhBuildOptions& options = {});

}  // namespace lucent::methods::random_walk
