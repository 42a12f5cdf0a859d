// test_voxel_paths_cpu.cpp: the CPU parts of voxel-paths: the grid, the gathered translucent triangles (world
// space, sigma_t in scene units), the reference Dijkstra against closed-form optical path lengths, and the
// heterogeneous fields (heterogeneous_field.h) and per-voxel coefficients.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "lucent/error.h"
#include "methods/voxel_paths/coefficient_field.h"
#include "methods/voxel_paths/voxel_dijkstra.h"
#include "methods/voxel_paths/voxel_grid.h"
#include "../test_support.h"

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

// Heterogeneous fields: `none` is 1; every field is deterministic and lies in [1, 1 + contrast] over a volume
// spanning many features (40^3 points in a cube of 6 x 6 x 6 feature sizes, off the origin).
TEST(VoxelPathsCpu, FieldsAreDeterministicAndBounded) {
  using namespace lucent::shader;
  const float scale = 0.3f, contrast = 4.0f;
  const glm::vec3 lower(-1.0f), upper(1.0f);
  for (int field : {kFieldNone, kFieldMarble, kFieldLayered}) {
    float lowest = 1e30f, highest = -1e30f;
    for (int k = 0; k < 40; ++k)
      for (int j = 0; j < 40; ++j)
        for (int i = 0; i < 40; ++i) {
          glm::vec3 p = glm::vec3(-0.83f) + (6.0f * scale / 40.0f) * glm::vec3(i, j, k);
          float m = field_multiplier(field, p, lower, upper, scale, contrast);
          ASSERT_EQ(m, field_multiplier(field, p, lower, upper, scale, contrast));
          if (field == kFieldNone) {
            ASSERT_EQ(m, 1.0f);
          }
          lowest = std::min(lowest, m), highest = std::max(highest, m);
        }
    EXPECT_GE(lowest, 1.0f) << field;
    EXPECT_LE(highest, 1.0f + contrast) << field;
    if (field != kFieldNone) {
      EXPECT_LT(lowest, 1.01f) << field;                    // soft matter somewhere
      EXPECT_GT(highest, 1.0f + 0.99f * contrast) << field;  // and dense matter
    }
  }
  // Value noise is continuous across lattice cells and in [0, 1).
  EXPECT_NEAR(field_value_noise(glm::vec3(2.0f - 1e-5f, 0.5f, 0.5f)), field_value_noise(glm::vec3(2.0f, 0.5f, 0.5f)),
              1e-3f);
}

// Marble veins are thin bands: vein >= 1/2 (m >= 1 + contrast / 2) on a fraction kMarbleVeinWidth = 10% of a
// cube of 8 vein periods (64^3 samples), within 3 points; the soft matrix (m < 1.01) covers more than 75%.
TEST(VoxelPathsCpu, MarbleVeinsAreThinDenseBands) {
  using namespace lucent::shader;
  const float scale = 0.25f, contrast = 4.0f;
  int dense = 0, soft = 0, total = 0;
  for (int k = 0; k < 64; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i, ++total) {
        glm::vec3 p = glm::vec3(0.37f, -1.1f, 0.2f) + (8.0f * scale / 64.0f) * glm::vec3(i, j, k);
        float m = field_multiplier(kFieldMarble, p, glm::vec3(0.0f), glm::vec3(1.0f), scale, contrast);
        dense += m >= 1.0f + 0.5f * contrast ? 1 : 0;
        soft += m < 1.01f ? 1 : 0;
      }
  const double dense_fraction = static_cast<double>(dense) / total, soft_fraction = static_cast<double>(soft) / total;
  fmt::print("marble: dense (vein >= 1/2) {:.4f}, soft (m < 1.01) {:.4f}\n", dense_fraction, soft_fraction);
  EXPECT_NEAR(dense_fraction, kMarbleVeinWidth, 0.03);
  EXPECT_GT(soft_fraction, 0.75);
}

// Layered: by depth below the bounding ellipsoid (a sphere of radius 1 here), scale 0.1: dense outer layer
// (depth < 0.1), soft middle (0.1 to 0.3), denser core (> 0.3); outside the ellipsoid counts as depth 0.
TEST(VoxelPathsCpu, LayeredProfileFollowsDepth) {
  using namespace lucent::shader;
  const glm::vec3 lower(-1.0f), upper(1.0f);
  auto m = [&](float radius) {
    return field_multiplier(kFieldLayered, radius * glm::normalize(glm::vec3(1, 2, -2)), lower, upper, 0.1f, 3.0f);
  };
  EXPECT_FLOAT_EQ(m(0.95f), 4.0f);
  EXPECT_FLOAT_EQ(m(0.8f), 1.0f);
  EXPECT_FLOAT_EQ(m(0.75f), 1.0f);
  EXPECT_FLOAT_EQ(m(0.5f), 2.5f);
  EXPECT_FLOAT_EQ(m(0.0f), 2.5f);
  EXPECT_FLOAT_EQ(m(1.2f), 4.0f);
  EXPECT_NEAR(ellipsoid_depth(glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(-2, -1, -3), glm::vec3(2, 1, 3)), 0.5f, 1e-6f);
}

// Per-voxel coefficients: with `none` each inside voxel holds its label's sigma_t (the per-label table, exactly)
// or sigma_tr; with marble, m sigma_t with m at the voxel centre; 0 outside.
TEST(VoxelPathsCpu, CoefficientFieldScalesTheMaterial) {
  lucent::Scene scene;
  scene.scale_mm = 10.0f;
  lucent::SceneObject box;
  box.mesh = lucent::make_box(glm::vec3(1.0f));
  lucent::Material material;
  material.sigma_a = glm::vec3(0.1f, 0.2f, 0.3f);
  material.sigma_s = glm::vec3(1.0f, 2.0f, 3.0f);
  material.g = glm::vec3(0.5f);
  box.material = material;
  scene.objects.push_back(box);
  VoxelGrid grid = unit_grid(8, 0.25f);
  grid.origin = glm::vec3(-1.0f);
  std::vector<std::uint32_t> labels(grid.voxel_count(), 0u);
  labels[grid.index({3, 4, 5})] = 1u;
  labels[grid.index({4, 4, 5})] = 1u;
  for (bool effective : {false, true}) {
    scene.objects[0].material->field = {};
    TranslucentTriangles triangles = gather_translucent_triangles(scene, effective);
    std::vector<glm::vec4> none = coefficient_field(grid, labels, triangles);
    for (int band = 0; band < 3; ++band)
      EXPECT_NEAR(none[grid.index({3, 4, 5})][band], triangles.sigma_t[1][band], 1e-5f * triangles.sigma_t[1][band]);
    EXPECT_EQ(none[0], glm::vec4(0.0f));
    // Marble with a 3 mm vein period: 0.3 scene units at 10 mm per unit.
    scene.objects[0].material->field.type = lucent::MediumFieldType::Marble;
    scene.objects[0].material->field.scale_mm = 3.0f;
    scene.objects[0].material->field.contrast = 2.0f;
    triangles = gather_translucent_triangles(scene, effective);
    std::vector<glm::vec4> veined = coefficient_field(grid, labels, triangles);
    const glm::vec3 p = grid.center({4, 4, 5});
    const float m = lucent::shader::field_multiplier(lucent::shader::kFieldMarble, p, glm::vec3(-0.5f), glm::vec3(0.5f),
                                                     0.3f, 2.0f);
    if (!effective) {
      EXPECT_NEAR(veined[grid.index({4, 4, 5})].g, m * 22.0f, 1e-4f);
    }
    EXPECT_GE(veined[grid.index({4, 4, 5})].g, none[grid.index({4, 4, 5})].g);
  }
}

// Two objects may share one volume file (one texture, each label over its own bounds); two different files are
// an error naming the second object.
TEST(VoxelPathsCpu, ObjectsShareOneVolumeFile) {
  auto volume_of = [](const std::string& source) {
    auto v = std::make_shared<lucent::MediumVolume>();
    v->source = source, v->size = glm::ivec3(1), v->values = {1.0f}, v->max_value = 1.0f;
    return v;
  };
  lucent::Scene scene;
  for (int i = 0; i < 2; ++i) {
    lucent::SceneObject object;
    object.name = fmt::format("box{}", i);
    object.mesh = lucent::make_box(glm::vec3(1.0f));
    lucent::Material material;
    material.sigma_a = glm::vec3(0.1f), material.sigma_s = glm::vec3(1.0f);
    material.field.type = lucent::MediumFieldType::Volume;
    material.field.volume = volume_of("volumes/a.json");  // loaded twice: two pointers, one file
    object.material = material;
    scene.objects.push_back(object);
  }
  EXPECT_NO_THROW(gather_translucent_triangles(scene));
  scene.objects[1].material->field.volume = volume_of("volumes/b.json");
  EXPECT_EQ(lucent::test::error_message([&] { gather_translucent_triangles(scene); }),
            "<built-in default>: voxel-paths supports one volume field per scene (object 'box1' has a second)");
}

// The medium where the field is m: m < 1 thins it at constant albedo (sigma_s scales too), m > 1 adds absorbing
// matter (sigma_s stays); sigma_tr of the modified medium by hand for m = 0.5 and m = 3.
TEST(VoxelPathsCpu, FieldMultiplierThinsOrAddsAbsorbingMatter) {
  using namespace lucent::shader;
  FieldMaterialGPU material{};
  material.sigma_a = glm::vec4(0.5f, 1.0f, 2.0f, 1.0f);  // sigma_tr costs; sigma_t = 2, 4, 8
  material.sigma_s = glm::vec4(1.5f, 3.0f, 6.0f, 0.0f);
  const glm::vec3 material_sigma_t(2.0f, 4.0f, 8.0f);
  material.g = glm::vec4(0.5f);
  for (float m : {0.5f, 3.0f}) {
    const glm::vec3 sigma_t = field_sigma_t(material, m), sigma_s = field_sigma_s(material, m);
    const glm::vec3 expected_s = m < 1.0f ? m * glm::vec3(material.sigma_s) : glm::vec3(material.sigma_s);
    EXPECT_EQ(sigma_s, expected_s);
    EXPECT_EQ(sigma_t, m * material_sigma_t);
    const glm::vec3 sigma_a = sigma_t - sigma_s;
    for (int band = 0; band < 3; ++band)
      EXPECT_NEAR(field_sigma_a(material, m)[band], sigma_a[band], 1e-6f * sigma_a[band]) << m;
    const glm::vec3 sigma_tr = glm::sqrt(3.0f * sigma_a * (sigma_a + 0.5f * sigma_s));
    const glm::vec3 c = field_coefficient(material, m);
    for (int band = 0; band < 3; ++band) EXPECT_NEAR(c[band], sigma_tr[band], 1e-5f * sigma_tr[band]) << m;
  }
  // Albedo is kept where the medium thins: 0.75 at m = 1 and m = 0.5, 0.25 at m = 3.
  EXPECT_FLOAT_EQ(field_sigma_s(material, 0.5f).x / field_sigma_t(material, 0.5f).x, 0.75f);
  EXPECT_FLOAT_EQ(field_sigma_s(material, 3.0f).x / field_sigma_t(material, 3.0f).x, 0.25f);
}

// Dijkstra in a two-slab medium (per-voxel coefficients, sigma_1 for x < 8, sigma_2 beyond, per band): along
// the axis from a source at x = 0 the optical distance is the piecewise integral sigma_1 (7.5 h) +
// sigma_2 (x - 7.5) h between voxel centres (the trapezoid edge across the boundary is exact for a step midway
// between centres), and sigma_1 x h before the boundary.
TEST(VoxelPathsCpu, DijkstraInATwoSlabMediumSumsThePiecewiseCosts) {
  const int r = 16;
  const float h = 0.1f;
  VoxelGrid grid = unit_grid(r, h);
  std::vector<std::uint32_t> labels(grid.voxel_count(), 1u);
  const glm::vec3 sigma_1(2.0f, 3.0f, 4.0f), sigma_2(5.0f, 1.0f, 7.0f);
  std::vector<glm::vec4> coefficients(grid.voxel_count());
  for (std::size_t i = 0; i < coefficients.size(); ++i)
    coefficients[i] = glm::vec4(grid.voxel(i).x < 8 ? sigma_1 : sigma_2, 0.0f);
  const glm::ivec3 s(0, 8, 8);
  std::vector<VoxelSource> sources = {{grid.index(s), glm::vec3(0.0f)}};
  std::vector<glm::vec3> n = dijkstra_optical_paths_per_voxel(grid, labels, coefficients, sources);
  for (int band = 0; band < 3; ++band)
    for (int x = 1; x < r; ++x) {
      const float fx = static_cast<float>(x);
      const float expected =
          x < 8 ? sigma_1[band] * fx * h : sigma_1[band] * 7.5f * h + sigma_2[band] * (fx - 7.5f) * h;
      EXPECT_NEAR(n[grid.index({x, 8, 8})][band], expected, 1e-5f * expected) << "band " << band << ", x " << x;
    }
}

}  // namespace
