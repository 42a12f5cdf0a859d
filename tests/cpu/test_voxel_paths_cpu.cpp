// test_voxel_paths_cpu.cpp: the CPU parts of voxel-paths: the grid, the gathered translucent triangles (world
// space, sigma_t in scene units) and the reference Dijkstra against closed-form optical path lengths.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "methods/voxel_paths/voxel_dijkstra.h"
#include "methods/voxel_paths/voxel_grid.h"

namespace {

using namespace lucent::methods::voxel_paths;

VoxelGrid unit_grid(int resolution, float h) {
  VoxelGrid grid;
  grid.resolution = resolution;
  grid.voxel_size = h;
  return grid;
}

TEST(VoxelPathsCpu, GridAroundIsACubeOverTheLongestExtentWithPadding) {
  VoxelGrid grid = grid_around(glm::vec3(-1, -0.5f, 0), glm::vec3(1, 0.5f, 0.25f), 64, 2);
  EXPECT_FLOAT_EQ(grid.voxel_size, 2.0f / 60.0f);
  EXPECT_NEAR(grid.origin.x, -1.0f - 2.0f * grid.voxel_size, 1e-6f);
  EXPECT_NEAR(grid.origin.z + 32.0f * grid.voxel_size, 0.125f, 1e-6f);  // centred
  EXPECT_EQ(grid.voxel(grid.index({5, 7, 9})), glm::ivec3(5, 7, 9));
}

TEST(VoxelPathsCpu, GathersTranslucentTrianglesInWorldSpaceAndSigmaTInSceneUnits) {
  lucent::Scene scene;
  scene.scale_mm = 10.0f;
  lucent::SceneObject opaque;
  opaque.mesh = lucent::make_box(glm::vec3(1.0f));
  scene.objects.push_back(opaque);
  lucent::SceneObject box;
  box.mesh = lucent::make_box(glm::vec3(1.0f, 2.0f, 3.0f));
  box.world_from_object[3] = glm::vec4(5, 0, 0, 1);
  lucent::Material material;
  material.sigma_a = glm::vec3(0.1f, 0.2f, 0.3f);
  material.sigma_s = glm::vec3(1.0f, 2.0f, 3.0f);
  box.material = material;
  scene.objects.push_back(box);
  TranslucentTriangles triangles = gather_translucent_triangles(scene);
  ASSERT_EQ(triangles.objects.size(), 1u);
  EXPECT_EQ(triangles.objects[0].label, 2u);  // object index 1
  EXPECT_EQ(triangles.corners.size(), 3u * triangles.objects[0].triangle_count);
  EXPECT_NEAR(triangles.lower.x, 4.5f, 1e-6f);
  EXPECT_NEAR(triangles.upper.z, 1.5f, 1e-6f);
  ASSERT_EQ(triangles.sigma_t.size(), 3u);
  EXPECT_NEAR(triangles.sigma_t[2].g, 22.0f, 1e-5f);  // (0.2 + 2) mm^-1 x 10 mm per unit
  EXPECT_EQ(triangles.sigma_t[1], glm::vec4(0.0f));
  // The diffusion's effective transport coefficient instead: sqrt(3 sigma_a sigma_t'), g = 0 here.
  TranslucentTriangles effective = gather_translucent_triangles(scene, true);
  EXPECT_NEAR(effective.sigma_t[2].g, 10.0f * std::sqrt(3.0f * 0.2f * 2.2f), 1e-4f);
}

// A homogeneous box filling the whole grid, one source voxel: n is sigma_t h times the octile distance
// (axis steps cost 1, face diagonals sqrt 2, space diagonals sqrt 3), per band.
TEST(VoxelPathsCpu, DijkstraMatchesClosedFormsInAHomogeneousBox) {
  const int r = 16;
  const float h = 0.05f;
  VoxelGrid grid = unit_grid(r, h);
  std::vector<std::uint32_t> labels(grid.voxel_count(), 1u);
  std::vector<glm::vec4> sigma_t = {glm::vec4(0.0f), glm::vec4(2.0f, 5.0f, 11.0f, 0.0f)};
  const glm::ivec3 s(3, 4, 5);
  const glm::vec3 n0(0.5f, 0.25f, 0.125f);
  std::vector<VoxelSource> sources = {{grid.index(s), n0}};
  std::vector<glm::vec3> n = dijkstra_optical_paths(grid, labels, sigma_t, sources);
  for (int band = 0; band < 3; ++band) {
    const float st = sigma_t[1][band];
    for (int steps = 1; steps <= 8; ++steps) {
      float axis = n[grid.index(s + glm::ivec3(steps, 0, 0))][band];
      float diagonal = n[grid.index(s + glm::ivec3(steps, steps, 0))][band];
      float space = n[grid.index(s + glm::ivec3(steps, steps, steps))][band];
      EXPECT_NEAR(axis, n0[band] + st * static_cast<float>(steps) * h, 1e-5f * axis);
      EXPECT_NEAR(diagonal, n0[band] + st * std::sqrt(2.0f) * static_cast<float>(steps) * h, 1e-5f * diagonal);
      EXPECT_NEAR(space, n0[band] + st * std::sqrt(3.0f) * static_cast<float>(steps) * h, 1e-5f * space);
    }
    // (4, 2, 1): one space diagonal, one face diagonal, two axis steps.
    float mixed = n[grid.index(s + glm::ivec3(4, 2, 1))][band];
    EXPECT_NEAR(mixed, n0[band] + st * h * (std::sqrt(3.0f) + std::sqrt(2.0f) + 2.0f), 1e-5f * mixed);
  }
  EXPECT_EQ(n[grid.index(s)], n0);
}

// Outside voxels are walls: around a wall the path takes the detour; unreachable voxels stay kUnreached; two
// sources give the minimum of their contributions; the trapezoid cost across a material boundary.
TEST(VoxelPathsCpu, DijkstraRespectsWallsSourcesAndMaterialBoundaries) {
  const int r = 8;
  VoxelGrid grid = unit_grid(r, 1.0f);
  std::vector<std::uint32_t> labels(grid.voxel_count(), 0u);
  // One row along x at y = z = 0: voxels 0..3 material 1, 4..7 material 2.
  for (int x = 0; x < r; ++x) labels[grid.index({x, 0, 0})] = x < 4 ? 1u : 2u;
  std::vector<glm::vec4> sigma_t = {glm::vec4(0.0f), glm::vec4(1.0f), glm::vec4(3.0f)};
  std::vector<VoxelSource> sources = {{grid.index({0, 0, 0}), glm::vec3(0.0f)},
                                      {grid.index({7, 0, 0}), glm::vec3(1.0f, 20.0f, 1.0f)}};
  std::vector<glm::vec3> n = dijkstra_optical_paths(grid, labels, sigma_t, sources);
  // From x = 0: 3 steps in material 1, one across the boundary (0.5 (1 + 3)), then 3 per step.
  EXPECT_FLOAT_EQ(n[grid.index({3, 0, 0})].g, 3.0f);
  EXPECT_FLOAT_EQ(n[grid.index({4, 0, 0})].g, 5.0f);
  EXPECT_FLOAT_EQ(n[grid.index({6, 0, 0})].g, 11.0f);
  // Band r: the source at x = 7 (n0 = 1) is closer to x = 6 (1 + 3 = 4) than x = 0's path (11).
  EXPECT_FLOAT_EQ(n[grid.index({6, 0, 0})].r, 4.0f);
  EXPECT_FLOAT_EQ(n[grid.index({1, 1, 0})].r, kUnreached);  // outside
}

}  // namespace
