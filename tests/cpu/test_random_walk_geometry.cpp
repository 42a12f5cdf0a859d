// test_random_walk_geometry.cpp: the random-walk method's CPU geometry: the scene's world-space triangles, the
// binned-SAH BVH (structure, closest hits and distances against brute force, refit), and the distance grid's
// conservative lower bound.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "../test_paths.h"
#include "lucent/error.h"
#include "lucent/scene.h"
#include "methods/random_walk/distance_grid.h"
#include "methods/random_walk/triangle_bvh.h"

namespace {

using namespace lucent;
using namespace lucent::methods::random_walk;

// A sphere, a torus through it and a box: overlapping objects, bunny-sized triangle counts, shared edges.
std::vector<TriangleGPU> rw_procedural_triangles() {
  Scene scene;
  SceneObject sphere, torus, box;
  sphere.mesh = make_sphere(1.0f, 64, 128);
  torus.mesh = make_torus(1.2f, 0.3f, 64, 32);
  torus.world_from_object = glm::mat4(1.0f);
  torus.world_from_object[3] = glm::vec4(0.4f, 0.2f, -0.1f, 1.0f);
  box.mesh = make_box(glm::vec3(0.5f, 2.5f, 0.5f));
  scene.objects = {sphere, torus, box};
  return gather_scene_triangles(scene).triangles;
}

std::optional<BvhHit> rw_brute_force_hit(std::span<const TriangleGPU> triangles, glm::vec3 o, glm::vec3 d, float t_max) {
  std::optional<BvhHit> best;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (auto h = intersect_triangle(triangles[t], o, d, t_max)) {
      t_max = h->t;
      best = BvhHit{h->t, h->u, h->v, static_cast<std::uint32_t>(t)};
    }
  return best;
}

float rw_brute_force_distance(std::span<const TriangleGPU> triangles, glm::vec3 p) {
  float best = std::numeric_limits<float>::infinity();
  for (const TriangleGPU& t : triangles) best = std::min(best, glm::length(p - closest_point_on_triangle(t, p)));
  return best;
}

glm::vec3 rw_random_point(std::mt19937& rng, float half_width) {
  std::uniform_real_distribution<float> u(-half_width, half_width);
  return {u(rng), u(rng), u(rng)};
}

glm::vec3 rw_random_direction(std::mt19937& rng) {
  std::normal_distribution<float> n;
  glm::vec3 d(n(rng), n(rng), n(rng));
  return glm::normalize(d);
}

// Rays from random points, about half of them aimed at a random point of the mesh's region; the BVH's nearest
// hit is the brute force's (the same triangle test), or both miss.
void rw_expect_hits_match(const TriangleBvh& bvh, std::span<const TriangleGPU> reference, int rays, unsigned seed) {
  std::mt19937 rng(seed);
  int hits = 0;
  for (int r = 0; r < rays; ++r) {
    glm::vec3 o = rw_random_point(rng, 2.5f);
    glm::vec3 d = r % 2 ? rw_random_direction(rng) : glm::normalize(rw_random_point(rng, 1.0f) - o);
    if (r % 5 == 0) {  // along an axis: infinite reciprocals in the box tests
      d = glm::vec3(0.0f);
      d[(r / 5) % 3] = (r / 5) % 2 ? 1.0f : -1.0f;
      if (r % 10 == 0) o[(r / 5) % 3] = -2.0f * d[(r / 5) % 3];  // in front of the mesh
    }
    float t_max = r % 7 == 0 ? 0.5f : 100.0f;
    auto expected = rw_brute_force_hit(reference, o, d, t_max);
    auto got = bvh.closest_hit(o, d, t_max);
    ASSERT_EQ(expected.has_value(), got.has_value()) << "ray " << r;
    if (!got) continue;
    ++hits;
    EXPECT_FLOAT_EQ(got->t, expected->t) << "ray " << r;
    EXPECT_TRUE(intersect_triangle(bvh.triangles[got->triangle], o, d, t_max).has_value());
  }
  EXPECT_GT(hits, rays / 4);
}

// Each node's box holds its children's (interior) or its triangles' corners (leaf).
void rw_expect_boxes_contain(const TriangleBvh& bvh) {
  auto contains = [](const BvhNodeGPU& outer, glm::vec3 lower, glm::vec3 upper) {
    return glm::all(glm::lessThanEqual(glm::vec3(outer.lower), lower)) &&
           glm::all(glm::greaterThanEqual(glm::vec3(outer.upper), upper));
  };
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
    const BvhNodeGPU& n = bvh.nodes[i];
    if (std::uint32_t count = node_count(n); count > 0) {
      for (std::uint32_t t = node_offset(n); t < node_offset(n) + count && t < bvh.triangles.size(); ++t) {
        const TriangleGPU& tri = bvh.triangles[t];
        glm::vec3 p0(tri.p0);
        for (glm::vec3 p : {p0, p0 + glm::vec3(tri.e1), p0 + glm::vec3(tri.e2)}) EXPECT_TRUE(contains(n, p, p)) << i;
      }
    } else {
      for (std::size_t c : {i + 1, std::size_t{node_offset(n)}}) {
        if (c < bvh.nodes.size()) {
          EXPECT_TRUE(contains(n, glm::vec3(bvh.nodes[c].lower), glm::vec3(bvh.nodes[c].upper))) << i << " " << c;
        }
      }
    }
  }
}

TEST(RandomWalkBvh, ClosestHitMatchesBruteForce) {
  std::vector<TriangleGPU> triangles = rw_procedural_triangles();
  ASSERT_GT(triangles.size(), 20000u);
  TriangleBvh bvh = build_triangle_bvh(triangles);
  rw_expect_hits_match(bvh, triangles, 2000, 1);
  EXPECT_FALSE(bvh.closest_hit(glm::vec3(0.0f, 10.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 100.0f).has_value());
  EXPECT_FALSE(build_triangle_bvh({}).closest_hit(glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), 1.0f).has_value());
}

// Depth-first layout: the left child is the next node, the right one further on; every triangle in one leaf,
// the leaves tiling the reordered array; each box holds its children's and its triangles.
TEST(RandomWalkBvh, StructureIsDepthFirstWithEveryTriangleInOneLeaf) {
  std::vector<TriangleGPU> triangles = rw_procedural_triangles();
  TriangleBvh bvh = build_triangle_bvh(triangles);
  ASSERT_EQ(bvh.triangles.size(), triangles.size());
  ASSERT_FALSE(bvh.nodes.empty());
  EXPECT_LE(bvh.depth, 64);
  std::vector<int> in_leaves(triangles.size(), 0), original_seen(triangles.size(), 0);
  rw_expect_boxes_contain(bvh);
  std::size_t leaves = 0;
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
    const BvhNodeGPU& n = bvh.nodes[i];
    if (std::uint32_t count = node_count(n); count > 0) {
      ++leaves;
      EXPECT_LE(count, 8u);
      for (std::uint32_t t = node_offset(n); t < node_offset(n) + count; ++t) {
        ASSERT_LT(t, triangles.size());
        ++in_leaves[t];
      }
    } else {
      const std::size_t right = node_offset(n);
      ASSERT_LT(i + 1, bvh.nodes.size());
      ASSERT_GT(right, i + 1);
      ASSERT_LT(right, bvh.nodes.size());
    }
  }
  EXPECT_EQ(bvh.nodes.size(), 2 * leaves - 1);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    EXPECT_EQ(in_leaves[t], 1) << "triangle slot " << t;
    std::uint32_t original = triangle_original_index(bvh.triangles[t]);
    ASSERT_LT(original, triangles.size());
    ++original_seen[original];
    EXPECT_EQ(glm::vec3(bvh.triangles[t].p0), glm::vec3(triangles[original].p0));
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) EXPECT_EQ(original_seen[t], 1) << "original triangle " << t;
}

// Many coincident triangles (no usable SAH plane) still give small leaves, through the median split.
TEST(RandomWalkBvh, CoincidentTrianglesSplitByMedian) {
  std::vector<TriangleGPU> triangles;
  for (std::uint32_t i = 0; i < 100; ++i)
    triangles.push_back(make_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, 0, i));
  TriangleBvh bvh = build_triangle_bvh(triangles);
  for (const BvhNodeGPU& n : bvh.nodes) EXPECT_LE(node_count(n), 4u);
  BvhBuildOptions single;
  single.leaf_triangles = single.max_leaf_triangles = 1;
  TriangleBvh singles = build_triangle_bvh(triangles, single);
  EXPECT_EQ(singles.nodes.size(), 2 * triangles.size() - 1);
  BvhBuildOptions bad;
  bad.leaf_triangles = 0;
  EXPECT_THROW(build_triangle_bvh(triangles, bad), Error);
  auto hit = bvh.closest_hit({0.2f, 0.2f, 1.0f}, {0.0f, 0.0f, -1.0f}, 10.0f);
  ASSERT_TRUE(hit.has_value());
  EXPECT_FLOAT_EQ(hit->t, 1.0f);
}

// Vertices moved (a twist and a swell): the refitted tree finds the same hits as a rebuild and as brute force.
TEST(RandomWalkBvh, RefitAfterMovingVerticesMatchesRebuild) {
  std::vector<TriangleGPU> triangles = rw_procedural_triangles();
  TriangleBvh bvh = build_triangle_bvh(triangles);
  std::vector<TriangleGPU> moved = triangles;
  auto move = [](glm::vec3 p) {
    float a = 0.8f * p.y, c = std::cos(a), s = std::sin(a);
    return glm::vec3(c * p.x - s * p.z, p.y, s * p.x + c * p.z) * (1.0f + 0.3f * p.y);
  };
  for (TriangleGPU& t : moved) {
    glm::vec3 p0(t.p0), p1 = p0 + glm::vec3(t.e1), p2 = p0 + glm::vec3(t.e2);
    t = make_triangle(move(p0), move(p1), move(p2), glm::vec3(t.n0), glm::vec3(t.n1), glm::vec3(t.n2),
                      triangle_object(t), triangle_original_index(t));
  }
  bvh.refit(moved);
  rw_expect_boxes_contain(bvh);
  TriangleBvh rebuilt = build_triangle_bvh(moved);
  std::mt19937 rng(7);
  for (int r = 0; r < 1000; ++r) {
    glm::vec3 o = rw_random_point(rng, 2.5f), d = glm::normalize(rw_random_point(rng, 1.0f) - o);
    auto a = bvh.closest_hit(o, d, 100.0f), b = rebuilt.closest_hit(o, d, 100.0f);
    ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << r;
    if (a) {
      EXPECT_FLOAT_EQ(a->t, b->t) << "ray " << r;
    }
  }
  rw_expect_hits_match(bvh, moved, 500, 8);
  std::vector<TriangleGPU> too_few(moved.begin(), moved.end() - 1);
  EXPECT_THROW(bvh.refit(too_few), Error);
}

TEST(RandomWalkBvh, ClosestPointOnTriangleIsNearestOfDenseSamples) {
  std::mt19937 rng(3);
  for (int k = 0; k < 200; ++k) {
    glm::vec3 a = rw_random_point(rng, 1.0f), b = rw_random_point(rng, 1.0f), c = rw_random_point(rng, 1.0f);
    TriangleGPU t = make_triangle(a, b, c, {}, {}, {}, 0, 0);
    glm::vec3 p = rw_random_point(rng, 2.0f);
    glm::vec3 q = closest_point_on_triangle(t, p);
    float exact = glm::length(p - q), sampled = std::numeric_limits<float>::infinity();
    const int n = 64;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
        sampled = std::min(sampled, glm::length(p - (a + (b - a) * float(i) / float(n) + (c - a) * float(j) / float(n))));
    float spacing = std::max({glm::length(b - a), glm::length(c - a), glm::length(c - b)}) / float(n);
    EXPECT_LE(exact, sampled + 1e-5f) << k;
    EXPECT_GE(exact, sampled - spacing) << k;
  }
  // A degenerate triangle (a segment) and a point of the plane inside.
  TriangleGPU segment = make_triangle({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {}, {}, {}, 0, 0);
  EXPECT_NEAR(glm::length(closest_point_on_triangle(segment, {1.5f, 1.0f, 0.0f}) - glm::vec3(1.5f, 0, 0)), 0.0f, 1e-6f);
  TriangleGPU flat = make_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {}, {}, {}, 0, 0);
  EXPECT_EQ(closest_point_on_triangle(flat, {0.25f, 0.25f, 3.0f}), glm::vec3(0.25f, 0.25f, 0.0f));
}

TEST(RandomWalkBvh, DistanceToNearestMatchesBruteForce) {
  std::vector<TriangleGPU> triangles = rw_procedural_triangles();
  TriangleBvh bvh = build_triangle_bvh(triangles);
  std::mt19937 rng(5);
  for (int k = 0; k < 400; ++k) {
    glm::vec3 p = rw_random_point(rng, k % 4 == 0 ? 6.0f : 1.8f);
    float expected = rw_brute_force_distance(triangles, p);
    EXPECT_FLOAT_EQ(bvh.distance_to_nearest(p), expected) << k;
    // Capped: the exact distance below the cap, the cap above it.
    float cap = 0.5f * expected + 0.01f;
    EXPECT_FLOAT_EQ(bvh.distance_to_nearest(p, cap), std::min(cap, expected)) << k;
    EXPECT_FLOAT_EQ(bvh.distance_to_nearest(p, 2.0f * expected + 0.01f), expected) << k;
  }
}

// D(c) - |x - c| with c the nearest centre: never above the true distance, within one cell diagonal of it
// inside the grid; still a lower bound outside it.
// Degenerate triangles (segments, points) are found by the distance search though they have no plane.
TEST(RandomWalkBvh, DistanceFindsDegenerateTriangles) {
  std::vector<TriangleGPU> triangles;
  for (std::uint32_t i = 0; i < 40; ++i) {
    float x = static_cast<float>(i);
    triangles.push_back(make_triangle({x, 0, 0}, {x + 0.5f, 0, 0}, {x + 1.0f, 0, 0}, {}, {}, {}, 0, 2 * i));
    triangles.push_back(make_triangle({x, 5, 0}, {x + 1, 5, 0}, {x, 5, 1}, {}, {}, {}, 0, 2 * i + 1));
  }
  TriangleBvh bvh = build_triangle_bvh(triangles);
  std::mt19937 rng(17);
  for (int k = 0; k < 200; ++k) {
    glm::vec3 p = rw_random_point(rng, 20.0f) + glm::vec3(20.0f, 2.5f, 0.0f);
    EXPECT_FLOAT_EQ(bvh.distance_to_nearest(p), rw_brute_force_distance(triangles, p)) << k;
  }
  EXPECT_NEAR(bvh.distance_to_nearest({10.3f, 1.0f, 0.0f}), 1.0f, 1e-6f);
}

TEST(RandomWalkDistanceGrid, LowerBoundIsConservativeAndTight) {
  std::vector<TriangleGPU> triangles = rw_procedural_triangles();
  TriangleBvh bvh = build_triangle_bvh(triangles);
  DistanceGrid grid = build_distance_grid(bvh, glm::vec3(-1.0f), glm::vec3(1.0f), {24, 0.1f});
  ASSERT_EQ(grid.cells, glm::ivec3(24));
  ASSERT_EQ(grid.distances.size(), 24u * 24u * 24u);
  EXPECT_NEAR(grid.cell_size, 2.4f / 24.0f, 1e-6f);
  EXPECT_NEAR(grid.origin.x, -1.2f, 1e-6f);
  for (int i = 0; i < 200; ++i) {  // the stored values: exact distances at the centres
    glm::ivec3 c(i % 24, (i * 7) % 24, (i * 13) % 24);
    float d = grid.distances[static_cast<std::size_t>(c.x + 24 * (c.y + 24 * c.z))];
    EXPECT_FLOAT_EQ(d, rw_brute_force_distance(triangles, grid.cell_centre(c)));
  }
  const float diagonal = std::sqrt(3.0f) * grid.cell_size;
  std::mt19937 rng(11);
  int positive = 0;
  for (int k = 0; k < 4000; ++k) {
    bool inside = k % 8 != 0;
    glm::vec3 p = rw_random_point(rng, inside ? 1.19f : 4.0f);
    float exact = bvh.distance_to_nearest(p), bound = grid.lower_bound_distance(p);
    EXPECT_GE(bound, 0.0f);
    EXPECT_LE(bound, exact * (1.0f + 1e-5f) + 1e-6f) << "point " << k;
    if (inside) {
      EXPECT_GE(bound, exact - diagonal * (1.0f + 1e-5f)) << "point " << k;
    }
    positive += bound > 0.0f;
  }
  EXPECT_GT(positive, 1000);
  EXPECT_TRUE(build_distance_grid(build_triangle_bvh({}), glm::vec3(-1.0f), glm::vec3(1.0f)).distances.empty());
}

// Objects in world space at a time: transforms and deformations applied, blobs skipped and counted, the
// translucent box; only the translucent objects on request.
TEST(RandomWalkSceneTriangles, GathersWorldSpaceTrianglesOfMeshObjects) {
  Scene scene = parse_scene(R"({
    "lights": [{ "direction": [0, -1, 0], "radiance": [1, 1, 1] }],
    "objects": [{ "shape": "sphere", "radius": 0.5, "translate": [2, 0, 0], "material": "Marble" },
                { "shape": "blobs", "segments": 16, "material": "Marble" },
                { "shape": "box", "size": [1, 1, 1], "deform": { "type": "wave", "amplitude": 0.2 },
                  "albedo": [0.5, 0.5, 0.5] }]
  })", "triangle scene", ".");
  SceneTriangles all = gather_scene_triangles(scene, 0.7);
  EXPECT_EQ(all.skipped_blobs, 1);
  const std::size_t sphere = scene.objects[0].mesh.indices.size() / 3, box = scene.objects[2].mesh.indices.size() / 3;
  ASSERT_EQ(all.triangles.size(), sphere + box);
  for (std::size_t t = 0; t < all.triangles.size(); ++t) {
    EXPECT_EQ(triangle_original_index(all.triangles[t]), t);
    EXPECT_EQ(triangle_object(all.triangles[t]), t < sphere ? 0u : 2u);
  }
  EXPECT_NEAR(all.translucent_lower.x, 1.5f, 1e-4f);
  EXPECT_NEAR(all.translucent_upper.x, 2.5f, 1e-4f);
  TriangleMesh waved = deformed_mesh(scene.objects[2].mesh, scene.objects[2].deformation, 0.7);
  int moved = 0;  // the wave leaves the base in place and moves the top
  for (std::size_t t = 0; t < box; ++t) {
    glm::vec3 p0(all.triangles[sphere + t].p0);
    EXPECT_EQ(p0, waved.positions[waved.indices[3 * t]]);
    moved += p0 != scene.objects[2].mesh.positions[waved.indices[3 * t]];
  }
  EXPECT_GT(moved, 0);
  SceneTriangles translucent = gather_scene_triangles(scene, 0.7, true);
  EXPECT_EQ(translucent.triangles.size(), sphere);
}

// The Stanford bunny of scenes/bunny_marble.json: build and distance-grid times (Release: the build well under
// 0.2 s), printed for the record.
TEST(RandomWalkBvh, BunnyBuildAndDistanceGrid) {
  const std::string path = std::string(LUCENT_SCENES_DIR) + "/bunny_marble.json";
  Scene scene;
  try {
    scene = load_scene(path);
  } catch (const Error& e) {
    GTEST_SKIP() << e.what();
  }
  SceneTriangles triangles = gather_scene_triangles(scene, 0.0, true);
  ASSERT_GT(triangles.triangles.size(), 60000u);
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  TriangleBvh bvh = build_triangle_bvh(triangles.triangles);
  auto t1 = clock::now();
  DistanceGrid grid = build_distance_grid(bvh, triangles.translucent_lower, triangles.translucent_upper);
  auto t2 = clock::now();
  DistanceGridOptions serial;
  serial.threads = 1;
  DistanceGrid serial_grid = build_distance_grid(bvh, triangles.translucent_lower, triangles.translucent_upper, serial);
  auto t3 = clock::now();
  EXPECT_EQ(serial_grid.distances, grid.distances) << "the same with one thread";
  auto seconds = [](clock::duration d) { return std::chrono::duration<double>(d).count(); };
  std::printf("bunny: %zu triangles, %zu nodes, depth %d, build %.3f s; distance grid %dx%dx%d in %.3f s "
              "(%u hardware threads), %.3f s on one\n",
              bvh.triangles.size(), bvh.nodes.size(), bvh.depth, seconds(t1 - t0), grid.cells.x, grid.cells.y,
              grid.cells.z, seconds(t2 - t1), std::thread::hardware_concurrency(), seconds(t3 - t2));
  EXPECT_EQ(std::max({grid.cells.x, grid.cells.y, grid.cells.z}), 64);
  std::mt19937 rng(13);
  glm::vec3 centre = 0.5f * (triangles.translucent_lower + triangles.translucent_upper);
  for (int k = 0; k < 300; ++k) {
    glm::vec3 p = centre + rw_random_point(rng, 1.0f);
    EXPECT_LE(grid.lower_bound_distance(p), bvh.distance_to_nearest(p) * (1.0f + 1e-5f) + 1e-6f);
  }
  rw_expect_hits_match(bvh, bvh.triangles, 200, 14);
}

}  // namespace
