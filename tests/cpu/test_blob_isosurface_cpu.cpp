// test_blob_isosurface_cpu.cpp: the blob field (gradient, periods, bound) and the marching-tetrahedra logic
// shared with the GPU: the Kuhn split tiles the cube with the stated orientations; every cube configuration
// and random fields give closed, consistently oriented surfaces; the CPU reference's blob frames are closed,
// oriented, of the right volume and topology, with vertices on the surface.
#include <bit>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../blob_surface_checks.h"
#include "geometry/blob_field.h"
#include "geometry/isosurface_cpu.h"
#include "geometry/marching_tetrahedra.h"

namespace {

using lucent::TriangleMesh;
using lucent::geometry::IsosurfaceGrid;
namespace sh = lucent::shader;

// ---- the field ---------------------------------------------------------------------------------------------

TEST(BlobField, GradientMatchesCentralDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coordinate(-1.2f, 1.2f), time(0.0f, 100.0f);
  const float step = 1e-3f;
  for (int k = 0; k < 200; ++k) {
    glm::vec3 x(coordinate(rng), 0.6f * coordinate(rng), 0.6f * coordinate(rng));
    float t = time(rng);
    glm::vec3 analytic = sh::blob_field_gradient(x, t), numeric;
    for (int axis = 0; axis < 3; ++axis) {
      glm::vec3 dx(0.0f);
      dx[axis] = step;
      numeric[axis] = (sh::blob_field(x + dx, t) - sh::blob_field(x - dx, t)) / (2.0f * step);
    }
    // float32 central differences: error ~ 1e-7 / 1e-3 from rounding plus O(step^2) from truncation.
    EXPECT_LT(glm::length(analytic - numeric), 2e-3f * glm::length(analytic) + 5e-4f) << "x = " << x.x << "," << x.y
                                                                                        << "," << x.z << " t = " << t;
  }
}

TEST(BlobField, EachCentreRepeatsWithItsOwnPeriod) {
  std::vector<float> periods;
  for (int i = 0; i < LUCENT_BLOB_COUNT; ++i) {
    float period = sh::blob_path(i).period;
    for (float t : {0.3f, 1.7f, 4.1f}) {
      EXPECT_LT(glm::length(sh::blob_center(i, t + period) - sh::blob_center(i, t)), 1e-4f) << "blob " << i;
      EXPECT_GT(glm::length(sh::blob_center(i, t + 0.5f * period) - sh::blob_center(i, t)), 0.05f) << "blob " << i;
    }
    for (float other : periods) EXPECT_NE(period, other) << "two blobs share a period";
    periods.push_back(period);
  }
}

// The body never reaches the faces of the bound (so the extraction grid's outer points are always outside
// and the forced-outside rule of mt_stored_sample never changes a sample of the blob scene).
TEST(BlobField, BodyStaysInsideItsBound) {
  glm::vec3 half = sh::blob_body_bound();
  const int n = 40;
  float largest = -1.0f;
  for (float t = 0.0f; t < 60.0f; t += 0.37f)
    for (int axis = 0; axis < 3; ++axis)
      for (float side : {-1.0f, 1.0f})
        for (int i = 0; i <= n; ++i)
          for (int j = 0; j <= n; ++j) {
            glm::vec3 p;
            p[axis] = side * half[axis];
            p[(axis + 1) % 3] = half[(axis + 1) % 3] * (2.0f * static_cast<float>(i) / n - 1.0f);
            p[(axis + 2) % 3] = half[(axis + 2) % 3] * (2.0f * static_cast<float>(j) / n - 1.0f);
            largest = std::max(largest, sh::blob_field(p, t));
          }
  EXPECT_LT(largest, 0.0f);
}

// ---- marching tetrahedra -----------------------------------------------------------------------------------

TEST(MarchingTetrahedra, KuhnTetrahedraTileTheCubeWithTheStatedOrientation) {
  float total = 0.0f;
  for (int tet = 0; tet < LUCENT_MT_TETS_PER_CELL; ++tet) {
    glm::vec3 v[4];
    for (int k = 0; k < 4; ++k) {
      int code = sh::mt_tet_corner(tet, k);
      v[k] = glm::vec3(sh::mt_corner_offset(code));
      if (k > 0) {
        EXPECT_EQ(code & sh::mt_tet_corner(tet, k - 1), sh::mt_tet_corner(tet, k - 1)) << "not a chain";
      }
    }
    float det = glm::determinant(glm::mat3(v[1] - v[0], v[2] - v[0], v[3] - v[0]));
    EXPECT_EQ(det, static_cast<float>(sh::mt_tet_parity(tet))) << "tetrahedron " << tet;
    total += std::abs(det) / 6.0f;
  }
  EXPECT_FLOAT_EQ(total, 1.0f);
}

// A grid of 3x3x3 cells whose 8 interior points take the given inside bits, the rest outside.
TriangleMesh cube_configuration(int cube_inside, IsosurfaceGrid* grid, std::vector<float>* samples) {
  grid->cells = glm::ivec3(3);
  grid->lower = glm::vec3(0.0f);
  grid->upper = glm::vec3(3.0f);
  samples->assign(grid->point_count(), -1.0f);
  for (int c = 0; c < 8; ++c)
    (*samples)[grid->point_index(glm::ivec3(1) + sh::mt_corner_offset(c))] = ((cube_inside >> c) & 1) ? 1.0f : -1.0f;
  return lucent::geometry::extract_blob_isosurface(*grid, *samples, 0.0f);
}

TEST(MarchingTetrahedra, EveryCubeConfigurationGivesAClosedOrientedSurface) {
  for (int cube_inside = 1; cube_inside < 256; ++cube_inside) {
    SCOPED_TRACE(cube_inside);
    IsosurfaceGrid grid;
    std::vector<float> samples;
    TriangleMesh mesh = cube_configuration(cube_inside, &grid, &samples);
    lucent::test::MeshTopology t = lucent::test::analyze_topology(mesh);
    EXPECT_EQ(t.open_edges, 0u);
    EXPECT_EQ(t.misoriented_edges, 0u);
    EXPECT_EQ(t.euler() % 2, 0);
    EXPECT_GT(lucent::test::signed_volume(mesh), 0.0);
    // A lone inside point (+1 among -1) encloses half of each of its 24 tetrahedra's corners: 24 x 1/6 x 1/8.
    if (std::popcount(static_cast<unsigned>(cube_inside)) == 1) {
      EXPECT_NEAR(lucent::test::signed_volume(mesh), 0.5, 1e-6);
    }
  }
}

TEST(MarchingTetrahedra, RandomFieldsGiveClosedOrientedSurfaces) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE(trial);
    IsosurfaceGrid grid;
    grid.cells = glm::ivec3(4, 5, 6);
    grid.lower = glm::vec3(-1.0f);
    grid.upper = glm::vec3(1.0f, 2.0f, 0.5f);
    std::vector<float> samples(grid.point_count());
    for (int z = 0; z <= grid.cells.z; ++z)
      for (int y = 0; y <= grid.cells.y; ++y)
        for (int x = 0; x <= grid.cells.x; ++x) {
          glm::ivec3 p(x, y, z);
          samples[grid.point_index(p)] = sh::mt_stored_sample(value(rng), p, grid.cells);
        }
    TriangleMesh mesh = lucent::geometry::extract_blob_isosurface(grid, samples, 0.0f);
    if (mesh.indices.empty()) continue;
    lucent::test::MeshTopology t = lucent::test::analyze_topology(mesh);
    EXPECT_EQ(t.open_edges, 0u);
    EXPECT_EQ(t.misoriented_edges, 0u);
    EXPECT_EQ(mesh.positions.size(), t.vertices) << "distinct vertices at the same position";
    EXPECT_EQ(t.euler() % 2, 0);
    EXPECT_GT(lucent::test::signed_volume(mesh), 0.0);
  }
}

// ---- the CPU reference on the blob scene -------------------------------------------------------------------

TEST(BlobIsosurfaceCpu, FramesAreClosedOrientedWithTheRightVolumeAndTopology) {
  IsosurfaceGrid grid = lucent::geometry::blob_grid(48);
  for (const lucent::test::BlobFrame& frame : lucent::test::blob_test_frames()) {
    SCOPED_TRACE(fmt::format("t = {} s", frame.time));
    std::vector<float> samples = lucent::geometry::sample_blob_field(grid, frame.time);
    TriangleMesh mesh = lucent::geometry::extract_blob_isosurface(grid, samples, frame.time);
    lucent::test::SurfaceMeasures m = lucent::test::measure_surface(mesh, grid, samples);
    lucent::test::expect_closed_oriented_surface(m);
    EXPECT_EQ(m.topology.components, frame.bodies);
  }
}

// Vertices lie on the zero set of the linear interpolant along their edge, so the true field there is small:
// the distance to the surface, |f| / |grad f| to first order, is at most 0.35 cells and 0.03 cells on average
// (measured on the 48-cell grid: at most 0.22 cells, at the neck of t = 6.25 s, and 0.015 on average).
TEST(BlobIsosurfaceCpu, VerticesLieOnTheSurface) {
  IsosurfaceGrid grid = lucent::geometry::blob_grid(48);
  float h = glm::length(grid.spacing()) / std::sqrt(3.0f);
  double worst = 0.0, sum = 0.0;
  std::size_t count = 0;
  for (float t : {0.0f, 6.25f, 9.5f}) {
    TriangleMesh mesh = lucent::geometry::extract_blob_isosurface(grid, t);
    for (const glm::vec3& p : mesh.positions) {
      double distance = std::abs(sh::blob_field(p, t)) / glm::length(sh::blob_field_gradient(p, t)) / h;
      worst = std::max(worst, distance);
      sum += distance;
      ++count;
    }
  }
  double mean = sum / static_cast<double>(count);
  RecordProperty("max_distance_cells", std::to_string(worst));
  RecordProperty("mean_distance_cells", std::to_string(mean));
  EXPECT_LT(worst, 0.35);
  EXPECT_LT(mean, 0.03);
}

}  // namespace
