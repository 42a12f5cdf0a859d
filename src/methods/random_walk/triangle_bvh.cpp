// triangle_bvh.cpp: the random-walk method's triangle BVH (see triangle_bvh.h): serial binned-SAH build,
// bottom-up refit, and the CPU ray and distance queries.
#include "methods/random_walk/triangle_bvh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include <fmt/format.h>

#include "lucent/error.h"
#include "lucent/mesh.h"

namespace lucent::methods::random_walk {
namespace {

float float_bits(std::uint32_t i) { return std::bit_cast<float>(i); }
std::uint32_t int_bits(float f) { return std::bit_cast<std::uint32_t>(f); }

struct Box {
  glm::vec3 lower{std::numeric_limits<float>::max()};
  glm::vec3 upper{std::numeric_limits<float>::lowest()};
  void grow(glm::vec3 p) { lower = glm::min(lower, p), upper = glm::max(upper, p); }
  void grow(const Box& b) { lower = glm::min(lower, b.lower), upper = glm::max(upper, b.upper); }
  // Half the surface area (the SAH only compares them); 0 for an empty box.
  float half_area() const {
    glm::vec3 d = glm::max(upper - lower, glm::vec3(0.0f));
    return d.x * d.y + d.y * d.z + d.z * d.x;
  }
};

Box triangle_box(const TriangleGPU& t) {
  glm::vec3 p0(t.p0);
  Box b;
  b.grow(p0), b.grow(p0 + glm::vec3(t.e1)), b.grow(p0 + glm::vec3(t.e2));
  return b;
}

Box node_box(const BvhNodeGPU& n) { return {glm::vec3(n.lower), glm::vec3(n.upper)}; }

void set_box(BvhNodeGPU& n, const Box& b) {
  n.lower = glm::vec4(b.lower, n.lower.w);
  n.upper = glm::vec4(b.upper, n.upper.w);
}

// Entry and exit distances of the ray through the box, (t0 <= t1 when it crosses within [0, t_max]). The exit
// distance is widened by a few float roundings so that a box never misses a hit on its surface through them.
// Zero direction components give infinite reciprocals; NaN products (0 * inf) are ignored by the comparisons.
bool ray_box(const Box& b, glm::vec3 origin, glm::vec3 inv_dir, float t_max, float& t_entry) {
  float t0 = 0.0f, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    float near = (b.lower[a] - origin[a]) * inv_dir[a];
    float far = (b.upper[a] - origin[a]) * inv_dir[a];
    if (near > far) std::swap(near, far);
    far *= 1.0f + 4.0f * std::numeric_limits<float>::epsilon();
    t0 = near > t0 ? near : t0;
    t1 = far < t1 ? far : t1;
    if (t0 > t1) return false;
  }
  t_entry = t0;
  return true;
}

float box_distance_squared(const Box& b, glm::vec3 p) {
  glm::vec3 d = glm::max(glm::max(b.lower - p, p - b.upper), glm::vec3(0.0f));
  return glm::dot(d, d);
}

// The serial binned-SAH builder: `order` holds triangle indices; each node covers a contiguous range of it.
class Builder {
 public:
  Builder(std::span<const TriangleGPU> triangles, const BvhBuildOptions& options, TriangleBvh& out)
      : options_(options), out_(out) {
    boxes_.reserve(triangles.size());
    centroids_.reserve(triangles.size());
    for (const TriangleGPU& t : triangles) {
      boxes_.push_back(triangle_box(t));
      centroids_.push_back(0.5f * (boxes_.back().lower + boxes_.back().upper));
    }
    order_.resize(triangles.size());
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<std::uint32_t>(i);
  }

  void build() {
    if (order_.empty()) return;
    out_.nodes.reserve(2 * order_.size() / static_cast<std::size_t>(std::max(1, options_.leaf_triangles)) + 1);
    node(0, static_cast<std::uint32_t>(order_.size()), 0);
  }

  const std::vector<std::uint32_t>& order() const { return order_; }

 private:
  struct Bin {
    Box box;
    std::uint32_t count = 0;
  };

  void make_leaf(std::size_t index, const Box& box, std::uint32_t begin, std::uint32_t end) {
    BvhNodeGPU& n = out_.nodes[index];
    n.lower = glm::vec4(box.lower, float_bits(begin));
    n.upper = glm::vec4(box.upper, float_bits(end - begin));
  }

  // Builds the subtree of order_[begin, end) at depth `depth`; returns its root's index.
  std::uint32_t node(std::uint32_t begin, std::uint32_t end, int depth) {
    const auto index = static_cast<std::uint32_t>(out_.nodes.size());
    out_.nodes.emplace_back();
    out_.depth = std::max(out_.depth, depth);
    Box box, centroid_box;
    for (std::uint32_t i = begin; i < end; ++i) box.grow(boxes_[order_[i]]), centroid_box.grow(centroids_[order_[i]]);
    const std::uint32_t count = end - begin;
    if (count <= static_cast<std::uint32_t>(options_.leaf_triangles) || depth >= options_.max_depth) {
      make_leaf(index, box, begin, end);
      return index;
    }
    const glm::vec3 extent = centroid_box.upper - centroid_box.lower;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    std::uint32_t mid = begin;
    if (extent[axis] > 0.0f) mid = sah_split(begin, end, axis, centroid_box.lower[axis], extent[axis], box);
    if (mid == kLeaf) {
      make_leaf(index, box, begin, end);
      return index;
    }
    if (mid <= begin || mid >= end) {  // no usable plane (coincident centroids, rounding): the median
      mid = begin + count / 2;
      std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                       [&](std::uint32_t a, std::uint32_t b) { return centroids_[a][axis] < centroids_[b][axis]; });
    }
    node(begin, mid, depth + 1);  // the left child: index + 1
    const std::uint32_t right = node(mid, end, depth + 1);
    BvhNodeGPU& n = out_.nodes[index];
    n.lower = glm::vec4(box.lower, float_bits(right));
    n.upper = glm::vec4(box.upper, float_bits(0u));
    return index;
  }

  static constexpr std::uint32_t kLeaf = std::numeric_limits<std::uint32_t>::max();

  // The cheapest of the bins - 1 planes along `axis`: partitions order_[begin, end) and returns the first index
  // of the right side; kLeaf when a leaf is cheaper and allowed.
  std::uint32_t sah_split(std::uint32_t begin, std::uint32_t end, int axis, float lower, float extent, const Box& box) {
    const int bins = std::clamp(options_.bins, 2, 64);
    std::array<Bin, 64> bin{};
    const float scale = static_cast<float>(bins) / extent;
    auto bin_of = [&](std::uint32_t t) {  // clamped as a float first: no out-of-range (or NaN) conversion
      const float f = (centroids_[t][axis] - lower) * scale;
      return f >= static_cast<float>(bins - 1) ? bins - 1 : (f > 0.0f ? static_cast<int>(f) : 0);
    };
    for (std::uint32_t i = begin; i < end; ++i) {
      Bin& b = bin[static_cast<std::size_t>(bin_of(order_[i]))];
      b.box.grow(boxes_[order_[i]]);
      ++b.count;
    }
    // Right-to-left sums: the area times count of the right side of plane k (after bin k).
    std::array<float, 64> right_cost{};
    Box right_box;
    std::uint32_t right_count = 0;
    for (int k = bins - 1; k > 0; --k) {
      right_box.grow(bin[static_cast<std::size_t>(k)].box);
      right_count += bin[static_cast<std::size_t>(k)].count;
      right_cost[static_cast<std::size_t>(k - 1)] = right_box.half_area() * static_cast<float>(right_count);
    }
    Box left_box;
    std::uint32_t left_count = 0;
    float best_cost = std::numeric_limits<float>::max();
    int best = -1;
    for (int k = 0; k + 1 < bins; ++k) {
      left_box.grow(bin[static_cast<std::size_t>(k)].box);
      left_count += bin[static_cast<std::size_t>(k)].count;
      if (left_count == 0 || left_count == end - begin) continue;
      float cost = left_box.half_area() * static_cast<float>(left_count) + right_cost[static_cast<std::size_t>(k)];
      if (cost < best_cost) best_cost = cost, best = k;
    }
    if (best < 0) return begin;  // all in one bin: the caller's median
    // Costs relative to one triangle test, a traversal step counted as one: leaf N, split 1 + (A_L N_L + A_R N_R) / A.
    const float area = box.half_area();
    const std::uint32_t count = end - begin;
    if (count <= static_cast<std::uint32_t>(options_.max_leaf_triangles) && area > 0.0f &&
        static_cast<float>(count) <= 1.0f + best_cost / area)
      return kLeaf;
    auto mid = std::partition(order_.begin() + begin, order_.begin() + end,
                              [&](std::uint32_t t) { return bin_of(t) <= best; });
    return static_cast<std::uint32_t>(mid - order_.begin());
  }

  const BvhBuildOptions& options_;
  TriangleBvh& out_;
  std::vector<Box> boxes_;
  std::vector<glm::vec3> centroids_;
  std::vector<std::uint32_t> order_;
};

constexpr int kStackSize = 128;  // > max depth + 1: a traversal pushes at most one node per level

}  // namespace

SceneTriangles gather_scene_triangles(const Scene& scene, double seconds, bool translucent_only) {
  SceneTriangles out;
  bool any_translucent = false;
  for (const SceneObject& object : scene.objects) any_translucent |= object.translucent() && object.blob_resolution == 0;
  Box translucent;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    if (object.blob_resolution > 0) {
      ++out.skipped_blobs;
      continue;
    }
    if (translucent_only && !object.translucent()) continue;
    const TriangleMesh world =
        object.deformation.type == DeformationType::None
            ? transformed(object.mesh, object.world_from_object)
            : transformed(deformed_mesh(object.mesh, object.deformation, seconds), object.world_from_object);
    const bool in_bounds = object.translucent() || !any_translucent;
    for (std::size_t t = 0; t + 2 < world.indices.size(); t += 3) {
      const std::uint32_t a = world.indices[t], b = world.indices[t + 1], c = world.indices[t + 2];
      out.triangles.push_back(make_triangle(world.positions[a], world.positions[b], world.positions[c],
                                            world.normals[a], world.normals[b], world.normals[c],
                                            static_cast<std::uint32_t>(i),
                                            static_cast<std::uint32_t>(out.triangles.size())));
      if (in_bounds) translucent.grow(triangle_box(out.triangles.back()));
    }
  }
  out.translucent_lower = translucent.lower, out.translucent_upper = translucent.upper;
  return out;
}

TriangleGPU make_triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 na, glm::vec3 nb, glm::vec3 nc,
                          std::uint32_t object, std::uint32_t original_index) {
  TriangleGPU t;
  t.p0 = glm::vec4(a, float_bits(object));
  t.e1 = glm::vec4(b - a, 0.0f);
  t.e2 = glm::vec4(c - a, 0.0f);
  t.n0 = glm::vec4(na, float_bits(original_index));
  t.n1 = glm::vec4(nb, 0.0f);
  t.n2 = glm::vec4(nc, 0.0f);
  return t;
}

std::uint32_t triangle_object(const TriangleGPU& triangle) { return int_bits(triangle.p0.w); }
std::uint32_t triangle_original_index(const TriangleGPU& triangle) { return int_bits(triangle.n0.w); }
std::uint32_t node_offset(const BvhNodeGPU& node) { return int_bits(node.lower.w); }
std::uint32_t node_count(const BvhNodeGPU& node) { return int_bits(node.upper.w); }

std::optional<TriangleHit> intersect_triangle(const TriangleGPU& triangle, glm::vec3 origin, glm::vec3 dir,
                                              float t_max) {
  const glm::vec3 e1(triangle.e1), e2(triangle.e2);
  const glm::vec3 pvec = glm::cross(dir, e2);
  const float det = glm::dot(e1, pvec);
  if (det == 0.0f || !std::isfinite(det)) return std::nullopt;  // parallel to the plane, or a degenerate triangle
  const float inv_det = 1.0f / det;
  const glm::vec3 tvec = origin - glm::vec3(triangle.p0);
  const float u = glm::dot(tvec, pvec) * inv_det;
  if (!(u >= 0.0f && u <= 1.0f)) return std::nullopt;
  const glm::vec3 qvec = glm::cross(tvec, e1);
  const float v = glm::dot(dir, qvec) * inv_det;
  if (!(v >= 0.0f && u + v <= 1.0f)) return std::nullopt;  // edges belong to both neighbours: no cracks
  const float t = glm::dot(e2, qvec) * inv_det;
  if (!(t > 0.0f && t < t_max)) return std::nullopt;
  return TriangleHit{t, u, v};
}

namespace {

inline glm::vec3 closest_point(const TriangleGPU& triangle, glm::vec3 p) {
  // Relative to corner 0: q = p - p0 and the corners 0, e1, e2.
  const glm::vec3 p0(triangle.p0), e1(triangle.e1), e2(triangle.e2);
  const glm::vec3 q = p - p0;
  // The foot of the perpendicular to the plane, in the barycentrics (u, v) of e1 and e2: the normal equations
  // of min |q - u e1 - v e2|.
  const float a11 = glm::dot(e1, e1), a12 = glm::dot(e1, e2), a22 = glm::dot(e2, e2);
  const float b1 = glm::dot(q, e1), b2 = glm::dot(q, e2);
  const float det = a11 * a22 - a12 * a12;
  if (det > 1e-12f * a11 * a22) {
    const float u = (a22 * b1 - a12 * b2) / det, v = (a11 * b2 - a12 * b1) / det;
    if (u >= 0.0f && v >= 0.0f && u + v <= 1.0f) return p0 + u * e1 + v * e2;
  }
  // Outside (or a degenerate triangle): the nearest point is on the boundary, the nearest of the three edges'.
  auto on_segment = [&](glm::vec3 from, glm::vec3 edge) {
    const float len2 = glm::dot(edge, edge);
    const float s = len2 > 0.0f ? std::clamp(glm::dot(q - from, edge) / len2, 0.0f, 1.0f) : 0.0f;
    return from + s * edge;
  };
  glm::vec3 best = on_segment(glm::vec3(0.0f), e1);
  float best_d2 = glm::dot(q - best, q - best);
  for (glm::vec3 c : {on_segment(glm::vec3(0.0f), e2), on_segment(e1, e2 - e1)}) {
    const float d2 = glm::dot(q - c, q - c);
    if (d2 < best_d2) best_d2 = d2, best = c;
  }
  return p0 + best;
}

}  // namespace

glm::vec3 closest_point_on_triangle(const TriangleGPU& triangle, glm::vec3 p) { return closest_point(triangle, p); }

TriangleBvh build_triangle_bvh(std::span<const TriangleGPU> triangles, const BvhBuildOptions& options) {
  if (options.max_depth < 0 || options.max_depth > kStackSize - 2)
    throw Error(fmt::format("triangle BVH: max depth {} outside [0, {}]", options.max_depth, kStackSize - 2));
  if (options.leaf_triangles < 1 || options.max_leaf_triangles < options.leaf_triangles)
    throw Error(fmt::format("triangle BVH: leaf sizes {} and {}: need 1 <= leaf_triangles <= max_leaf_triangles",
                            options.leaf_triangles, options.max_leaf_triangles));
  if (triangles.size() >= (std::size_t{1} << 31))
    throw Error(fmt::format("triangle BVH: {} triangles, more than an index holds", triangles.size()));
  TriangleBvh bvh;
  Builder builder(triangles, options, bvh);
  builder.build();
  bvh.triangles.reserve(triangles.size());
  for (std::uint32_t t : builder.order()) bvh.triangles.push_back(triangles[t]);
  return bvh;
}

void TriangleBvh::refit() {
  for (std::size_t i = nodes.size(); i-- > 0;) {  // children follow their parent: reverse order is bottom-up
    BvhNodeGPU& n = nodes[i];
    Box box;
    if (const std::uint32_t count = node_count(n); count > 0) {
      const std::uint32_t first = node_offset(n);
      for (std::uint32_t t = first; t < first + count; ++t) box.grow(triangle_box(triangles[t]));
    } else {
      box.grow(node_box(nodes[i + 1]));
      box.grow(node_box(nodes[node_offset(n)]));
    }
    set_box(n, box);
  }
}

void TriangleBvh::refit(std::span<const TriangleGPU> moved) {
  if (moved.size() != triangles.size())
    throw Error(fmt::format("triangle BVH refit: {} triangles for a tree of {}", moved.size(), triangles.size()));
  for (TriangleGPU& t : triangles) {
    const std::uint32_t original = triangle_original_index(t);
    if (original >= moved.size() || triangle_original_index(moved[original]) != original)
      throw Error(fmt::format("triangle BVH refit: triangle {} is not at its original index", original));
    t = moved[original];
  }
  refit();
}

std::optional<BvhHit> TriangleBvh::closest_hit(glm::vec3 origin, glm::vec3 dir, float t_max) const {
  if (nodes.empty()) return std::nullopt;
  const glm::vec3 inv_dir = 1.0f / dir;
  std::optional<BvhHit> hit;
  float t_entry = 0.0f;
  if (!ray_box(node_box(nodes[0]), origin, inv_dir, t_max, t_entry)) return std::nullopt;
  std::array<std::uint32_t, kStackSize> stack;
  int top = 0;
  std::uint32_t current = 0;
  for (;;) {
    const BvhNodeGPU& n = nodes[current];
    if (const std::uint32_t count = node_count(n); count > 0) {
      const std::uint32_t first = node_offset(n);
      for (std::uint32_t t = first; t < first + count; ++t)
        if (auto h = intersect_triangle(triangles[t], origin, dir, t_max)) {
          t_max = h->t;
          hit = BvhHit{h->t, h->u, h->v, t};
        }
    } else {
      const std::uint32_t left = current + 1, right = node_offset(n);
      float t_left = 0.0f, t_right = 0.0f;
      const bool hit_left = ray_box(node_box(nodes[left]), origin, inv_dir, t_max, t_left);
      const bool hit_right = ray_box(node_box(nodes[right]), origin, inv_dir, t_max, t_right);
      if (hit_left && hit_right) {  // the nearer first
        const bool left_first = t_left <= t_right;
        stack[static_cast<std::size_t>(top++)] = left_first ? right : left;
        current = left_first ? left : right;
        continue;
      }
      if (hit_left || hit_right) {
        current = hit_left ? left : right;
        continue;
      }
    }
    if (top == 0) break;
    current = stack[static_cast<std::size_t>(--top)];
  }
  return hit;
}

float TriangleBvh::distance_to_nearest(glm::vec3 p, float max_distance) const {
  std::optional<NearestTriangle> nearest = nearest_triangle(p, max_distance);
  return nearest ? nearest->distance : max_distance;
}

std::optional<NearestTriangle> TriangleBvh::nearest_triangle(glm::vec3 p, float max_distance,
                                                             std::uint32_t guess) const {
  if (nodes.empty()) return std::nullopt;
  float best2 = max_distance * max_distance;  // squared; infinity stays infinity
  std::uint32_t best = kNoTriangle;
  auto try_triangle = [&](std::uint32_t t) {
    // The distance to the triangle's plane, a lower bound, first: it rules most candidates out at less cost.
    const glm::vec3 n = glm::cross(glm::vec3(triangles[t].e1), glm::vec3(triangles[t].e2));
    const float h = glm::dot(p - glm::vec3(triangles[t].p0), n), n2 = glm::dot(n, n);
    if (n2 > 0.0f && h * h >= best2 * n2) return;  // (a degenerate triangle has no plane)
    const glm::vec3 d = p - closest_point(triangles[t], p);
    if (const float d2 = glm::dot(d, d); d2 < best2) best2 = d2, best = t;
  };
  auto result = [&]() -> std::optional<NearestTriangle> {
    if (best == kNoTriangle) return std::nullopt;
    return NearestTriangle{std::sqrt(best2), best};
  };
  if (guess < triangles.size()) try_triangle(guess);
  if (box_distance_squared(node_box(nodes[0]), p) >= best2) return result();
  std::array<std::uint32_t, kStackSize> stack;
  int top = 0;
  std::uint32_t current = 0;
  for (;;) {
    const BvhNodeGPU& n = nodes[current];
    if (const std::uint32_t count = node_count(n); count > 0) {
      const std::uint32_t first = node_offset(n);
      for (std::uint32_t t = first; t < first + count; ++t) try_triangle(t);
    } else {
      const std::uint32_t left = current + 1, right = node_offset(n);
      const float d_left = box_distance_squared(node_box(nodes[left]), p);
      const float d_right = box_distance_squared(node_box(nodes[right]), p);
      const bool near_left = d_left < best2, near_right = d_right < best2;
      if (near_left && near_right) {
        const bool left_first = d_left <= d_right;
        stack[static_cast<std::size_t>(top++)] = left_first ? right : left;
        current = left_first ? left : right;
        continue;
      }
      if (near_left || near_right) {
        current = near_left ? left : right;
        continue;
      }
    }
    // Pop, skipping nodes that a nearer triangle found since has ruled out.
    bool found = false;
    while (top > 0) {
      current = stack[static_cast<std::size_t>(--top)];
      if (box_distance_squared(node_box(nodes[current]), p) < best2) {
        found = true;
        break;
      }
    }
    if (!found) break;
  }
  return result();
}

}  // namespace lucent::methods::random_walk
