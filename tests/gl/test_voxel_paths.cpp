// test_voxel_paths.cpp: the GPU parts of voxel-paths: the parity voxelization reproduces a sphere's volume and
// a box's exact cell count, and the parallel relaxation converges to the CPU Dijkstra's optical path lengths.
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "image_compare.h"
#include "lucent/lucent.h"
#include "methods/voxel_paths/coefficient_field.h"
#include "methods/voxel_paths/relaxation_solver.h"
#include "methods/voxel_paths/voxel_dijkstra.h"
#include "methods/voxel_paths/voxelizer.h"
#include "render/scene_gpu.h"
#include "../test_paths.h"

namespace {

using namespace lucent::methods::voxel_paths;

lucent::Scene scene_with(lucent::TriangleMesh mesh, glm::vec3 translation = glm::vec3(0.0f)) {
  lucent::Scene scene;
  scene.scale_mm = 10.0f;
  lucent::SceneObject object;
  object.mesh = std::move(mesh);
  object.world_from_object[3] = glm::vec4(translation, 1.0f);
  lucent::Material material;
  material.sigma_a = glm::vec3(0.0032f, 0.017f, 0.048f);  // marble-like, mm^-1
  material.sigma_s = glm::vec3(2.19f, 2.62f, 3.00f);
  object.material = material;
  scene.objects.push_back(object);
  return scene;
}

// The inside voxel whose centre is nearest `target`.
std::size_t nearest_inside_voxel(const VoxelGrid& grid, const std::vector<std::uint32_t>& labels, glm::vec3 target) {
  std::size_t best = 0;
  float best_distance = 1e30f;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    float d = glm::length(grid.center(grid.voxel(i)) - target);
    if (labels[i] != 0 && d < best_distance) best = i, best_distance = d;
  }
  return best;
}

std::size_t inside_count(const std::vector<std::uint32_t>& labels) {
  std::size_t n = 0;
  for (std::uint32_t label : labels) n += label != 0 ? 1 : 0;
  return n;
}

// Sphere of radius 1 (64 rings x 128 segments) on grids of 32 and 64 voxels: the count times h^3 is the
// sphere's volume within 1.5% at R = 32 and 0.5% at R = 64 (the tessellation itself is 0.2% smaller; the rest
// is surface voxels whose centres fall either side, which mostly cancel).
TEST(VoxelPaths, VoxelizedSphereHasTheSpheresVolume) {
  lucent::test::ensure_gl_context();
  const lucent::Scene scene = scene_with(lucent::make_sphere(1.0f, 64, 128), glm::vec3(0.3f, -0.2f, 0.1f));
  const TranslucentTriangles triangles = gather_translucent_triangles(scene);
  Voxelizer voxelizer;
  for (auto [resolution, tolerance] : {std::pair{32, 0.015}, std::pair{64, 0.005}}) {
    const VoxelGrid grid = grid_around(triangles.lower, triangles.upper, resolution, 2);
    voxelizer.voxelize(triangles, grid);
    const std::vector<std::uint32_t> labels = voxelizer.read_labels();
    const double expected = 4.0 / 3.0 * std::numbers::pi / std::pow(static_cast<double>(grid.voxel_size), 3.0);
    const auto count = static_cast<double>(inside_count(labels));
    fmt::print("R = {}: {} voxels inside, sphere volume / h^3 = {:.1f} ({:+.3f}%)\n", resolution, count, expected,
               100.0 * (count / expected - 1.0));
    EXPECT_NEAR(count / expected, 1.0, tolerance) << "R = " << resolution;
    // Every inside voxel's centre lies within one voxel diagonal of the sphere.
    for (std::size_t i = 0; i < labels.size(); ++i) {
      if (labels[i] == 0) continue;
      float distance = glm::length(grid.center(grid.voxel(i)) - glm::vec3(0.3f, -0.2f, 0.1f));
      ASSERT_LT(distance, 1.0f + 0.87f * grid.voxel_size);
    }
  }
}

// A 2 x 1 x 0.5 box whose faces lie on voxel boundaries: exactly its cell count, with or without padding. The
// columns through the diagonals of its top and bottom faces cross two triangles' shared edge: counted once. A
// cube at R = 256: a face triangle's footprint spans 256 x 256 columns, past llvmpipe's 65,535 loop iterations for
// one invocation; the voxelization splits its rows over slices (a cut loop leaves columns unflipped).
TEST(VoxelPaths, VoxelizedBoxIsExactlyItsCells) {
  lucent::test::ensure_gl_context();
  const lucent::Scene scene = scene_with(lucent::make_box(glm::vec3(2.0f, 1.0f, 0.5f)), glm::vec3(1.0f, 2.0f, 3.0f));
  const TranslucentTriangles triangles = gather_translucent_triangles(scene);
  Voxelizer voxelizer;
  for (auto [resolution, padding] : {std::pair{64, 0}, std::pair{64, 4}, std::pair{32, 8}}) {
    const VoxelGrid grid = grid_around(triangles.lower, triangles.upper, resolution, padding);
    voxelizer.voxelize(triangles, grid);
    const std::vector<std::uint32_t> labels = voxelizer.read_labels();
    const std::size_t inner = static_cast<std::size_t>(resolution - 2 * padding);
    EXPECT_EQ(inside_count(labels), inner * inner / 2 * inner / 4) << "R = " << resolution << ", padding " << padding;
  }
  const lucent::Scene cube = scene_with(lucent::make_box(glm::vec3(1.0f)), glm::vec3(0.0f));
  const TranslucentTriangles cube_triangles = gather_translucent_triangles(cube);
  const VoxelGrid grid = grid_around(cube_triangles.lower, cube_triangles.upper, 256, 0);
  voxelizer.voxelize(cube_triangles, grid);
  EXPECT_EQ(inside_count(voxelizer.read_labels()), std::size_t{256} * 256 * 256) << "cube, R = 256";
}

// GPU relaxation against the CPU Dijkstra on the same voxels: a sphere and a box, three sources each with
// different initial values per band. Tolerance: 1e-5 relative per voxel and band (both sum the same float
// edge costs; a GPU may fuse multiply-adds), and the same voxels reached.
class Relaxation : public ::testing::TestWithParam<RelaxationSchedule> {};

TEST_P(Relaxation, ConvergesToDijkstra) {
  lucent::test::ensure_gl_context();
  Voxelizer voxelizer;
  RelaxationSolver solver(GetParam());
  CoefficientField field;
  struct Case {
    const char* name;
    lucent::TriangleMesh mesh;
    int resolution;
  };
  Case cases[] = {{"sphere", lucent::make_sphere(1.0f, 32, 64), 32},
                  {"box", lucent::make_box(glm::vec3(2.0f, 1.0f, 0.5f)), 32},
                  {"sphere", lucent::make_sphere(1.0f, 64, 128), 64}};
  for (Case& c : cases) {
    const lucent::Scene scene = scene_with(c.mesh);
    const TranslucentTriangles triangles = gather_translucent_triangles(scene);
    const VoxelGrid grid = grid_around(triangles.lower, triangles.upper, c.resolution, 2);
    voxelizer.voxelize(triangles, grid);
    const std::vector<std::uint32_t> labels = voxelizer.read_labels();
    field.fill(grid, voxelizer.labels_buffer(), triangles);
    // Sources: the inside voxels nearest three points, with per-band initial values.
    std::vector<VoxelSource> sources;
    const glm::vec3 targets[3] = {{0.9f, 0.0f, 0.0f}, {-0.3f, -0.4f, 0.1f}, {0.0f, 0.2f, -0.2f}};
    for (int s = 0; s < 3; ++s)
      sources.push_back({nearest_inside_voxel(grid, labels, targets[s]),
                         glm::vec3(0.1f * static_cast<float>(s), 2.0f - static_cast<float>(s), 0.5f)});
    const std::vector<glm::vec3> expected = dijkstra_optical_paths(grid, labels, triangles.sigma_t, sources);
    solver.reset(grid, sources);
    glFinish();
    auto start = std::chrono::steady_clock::now();
    RelaxationStats stats = solver.solve(grid, voxelizer.labels_buffer(), field.buffer(), 8, 4 * c.resolution);
    glFinish();
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    fmt::print("{} R = {}: {} inside voxels, converged {} after {} sweeps, {:.1f} ms ({:.2f} ms per sweep)\n",
               c.name, c.resolution, inside_count(labels), stats.converged, stats.iterations, ms,
               ms / stats.iterations);
    EXPECT_TRUE(stats.converged) << c.name << " R = " << c.resolution;
    const std::vector<glm::vec3> actual = solver.read_distances();
    std::size_t mismatches = 0;
    float worst = 0.0f;
    for (std::size_t i = 0; i < labels.size(); ++i)
      for (int band = 0; band < 3; ++band) {
        float e = expected[i][band], a = actual[i][band];
        bool reached = e < kUnreached;
        if (reached != (a < kUnreached)) {
          ++mismatches;
          continue;
        }
        if (!reached) continue;
        float error = std::abs(a - e) / std::max(e, 1e-3f);
        worst = std::max(worst, error);
        if (error > 1e-5f) ++mismatches;
      }
    fmt::print("  worst relative difference {:.2e}\n", worst);
    EXPECT_EQ(mismatches, 0u) << c.name << " R = " << c.resolution << ", worst " << worst;
  }
}

}  // namespace

namespace {

lucent::Scene side_lit_sphere(const std::string& method) {
  return lucent::parse_scene(fmt::format(R"({{
    "scale_mm": 1,
    "camera": {{ "eye": [0, 0, 6], "target": [0, 0, 0], "fov_y_deg": 22 }},
    "lights": [{{ "direction": [-1, 0, 0], "radiance": [1, 1, 1] }}],
    "objects": [{{ "shape": "sphere", "radius": 1, "segments": 96,
                  "material": {{ "sigma_a": [0.01, 0.02, 0.04], "sigma_s": [0.5, 0.6, 0.7], "g": 0 }} }}],
    "method": {},
    "render": {{ "width": 64, "height": 64, "frames": 1 }} }})",
                                         method),
                             "side-lit sphere", ".");
}

// The whole method on a sphere lit from +x: the lit half is bright, brightness falls off toward the far side
// as exp(-sigma_t d) (optically thin here: sigma_t d ~ 0.6 to 1.2 across the sphere; measured lit / far ratio
// 1.87 at R = 32 and 1.90 at R = 64), every pixel is finite.
TEST(VoxelPaths, SideLitSphereIsBrightestOnTheLitSide) {
  lucent::test::ensure_gl_context();
  for (int resolution : {32, 64}) {
    lucent::Scene scene = side_lit_sphere(fmt::format(R"({{"name": "voxel-paths", "resolution": {}, "light_map_size": 256, "specular": false}})", resolution));
    lucent::OffscreenFramebuffer framebuffer(64, 64);
    lucent::Renderer renderer(scene);
    renderer.render(scene.camera, {framebuffer.id(), 64, 64});
    lucent::ImageRGBA32F image = renderer.read_radiance();
    double lit = 0.0, dark = 0.0;
    int lit_n = 0, dark_n = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const float* p = &image.pixels[(static_cast<std::size_t>(y) * 64 + static_cast<std::size_t>(x)) * 4];
        ASSERT_TRUE(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
        if (p[3] <= 0.0f) continue;
        if (x > 40) lit += p[1], ++lit_n;
        if (x < 24) dark += p[1], ++dark_n;
      }
    ASSERT_GT(lit_n, 0);
    ASSERT_GT(dark_n, 0);
    lit /= lit_n, dark /= dark_n;
    for (const auto& pass : renderer.last_frame_timings().passes) fmt::print("  {} {:.2f} ms\n", pass.name, pass.ms);
    fmt::print("R = {}: mean green lit side {:.4f}, far side {:.4f}, ratio {:.2f}\n", resolution, lit, dark, lit / dark);
    EXPECT_GT(lit, 0.05);
    EXPECT_GT(dark, 0.0);
    EXPECT_GT(lit, 1.5 * dark);
    EXPECT_LT(lit, 3.0 * dark);
  }
}

// Heterogeneous media: the GPU fills the per-voxel coefficients from the field (fill_coefficients.comp) as the
// CPU evaluation of the same header does (relative 1e-4 for sigma_t, 1e-3 for sigma_tr, on all but at most 0.1%
// of the voxel bands: float rounding may move a voxel centre across a layer boundary or a noise cell). sigma_tr
// gets the wider bound because it is ill-conditioned in m where m > 1: sigma_a = m sigma_a + (m - 1) sigma_s
// grows by sigma_s / sigma_a (about 1000 for marble) times the relative change of m, so a rounding difference of
// m of a few 1e-7 (GPU compilers contract to fused multiply-adds) changes sigma_tr by up to ~1e-3; measured worst
// 3.4e-4 on llvmpipe, 7.5e-4 on an NVIDIA H100, against 3e-5 for sigma_t). And the relaxation on those
// coefficients converges to the CPU Dijkstra on the same (read-back) coefficients within 1e-5 relative, as in
// the homogeneous test. Marble veins, skin-like layers and a volume field (GPU trilinear by texelFetch against
// MediumVolume::multiplier), sigma_t and sigma_tr costs, sphere R = 32.
TEST_P(Relaxation, HeterogeneousConvergesToDijkstra) {
  lucent::test::ensure_gl_context();
  Voxelizer voxelizer;
  RelaxationSolver solver(GetParam());
  CoefficientField field;
  // A volume of multipliers in [0.3, 3.3] on a coarse, anisotropic grid, so that trilinear weights matter.
  auto volume = std::make_shared<lucent::MediumVolume>();
  volume->size = glm::ivec3(7, 5, 9);
  for (int i = 0; i < 7 * 5 * 9; ++i) volume->values.push_back(0.3f + 3.0f * static_cast<float>((i * 37) % 64) / 63.0f);
  volume->max_value = 3.3f;
  auto field_of = [&](lucent::MediumFieldType type, float scale_mm, float contrast) {
    lucent::MediumField f;
    f.type = type, f.scale_mm = scale_mm, f.contrast = contrast;
    if (type == lucent::MediumFieldType::Volume) f.volume = volume;
    return f;
  };
  struct Case {
    const char* name;
    lucent::MediumField field;
    bool effective;
  };
  // scene_with: 10 mm per scene unit.
  const Case cases[] = {{"marble sigma_t", field_of(lucent::MediumFieldType::Marble, 4.0f, 4.0f), false},
                        {"marble sigma_tr", field_of(lucent::MediumFieldType::Marble, 4.0f, 4.0f), true},
                        {"layered sigma_t", field_of(lucent::MediumFieldType::Layered, 1.5f, 3.0f), false},
                        {"volume sigma_tr", field_of(lucent::MediumFieldType::Volume, 10.0f, 0.0f), true}};
  for (const Case& c : cases) {
    lucent::Scene scene = scene_with(lucent::make_sphere(1.0f, 32, 64));
    scene.objects[0].material->field = c.field;
    const TranslucentTriangles triangles = gather_translucent_triangles(scene, c.effective);
    const VoxelGrid grid = grid_around(triangles.lower, triangles.upper, 32, 2);
    voxelizer.voxelize(triangles, grid);
    const std::vector<std::uint32_t> labels = voxelizer.read_labels();
    field.fill(grid, voxelizer.labels_buffer(), triangles);
    const std::vector<glm::vec4> gpu = field.read();
    const std::vector<glm::vec4> cpu = coefficient_field(grid, labels, triangles);
    std::size_t field_mismatches = 0, bands = 0;
    float lowest = 1e30f, highest = 0.0f, worst_field = 0.0f;
    for (std::size_t i = 0; i < labels.size(); ++i) {
      if (labels[i] == 0) {
        ASSERT_EQ(gpu[i], glm::vec4(0.0f));
        continue;
      }
      for (int band = 0; band < 3; ++band, ++bands)
      {
        const float difference = std::abs(gpu[i][band] - cpu[i][band]);
        field_mismatches += difference > (c.effective ? 1e-3f : 1e-4f) * cpu[i][band] ? 1 : 0;
        worst_field = std::max(worst_field, difference / cpu[i][band]);
      }
      lowest = std::min(lowest, gpu[i].g), highest = std::max(highest, gpu[i].g);
    }
    EXPECT_LE(field_mismatches, bands / 1000) << c.name;
    EXPECT_GT(highest, 1.5f * lowest) << c.name;  // heterogeneous indeed
    // Sources: the inside voxels nearest two points.
    std::vector<VoxelSource> sources;
    const glm::vec3 targets[2] = {{0.9f, 0.0f, 0.0f}, {-0.3f, -0.4f, 0.1f}};
    for (int s = 0; s < 2; ++s)
      sources.push_back({nearest_inside_voxel(grid, labels, targets[s]), glm::vec3(0.5f * static_cast<float>(s), 1.0f, 0.25f)});
    const std::vector<glm::vec3> expected = dijkstra_optical_paths_per_voxel(grid, labels, gpu, sources);
    const std::vector<glm::vec3> from_cpu_field = dijkstra_optical_paths_per_voxel(grid, labels, cpu, sources);
    solver.reset(grid, sources);
    RelaxationStats stats = solver.solve(grid, voxelizer.labels_buffer(), field.buffer(), 8, 256);
    EXPECT_TRUE(stats.converged) << c.name;
    const std::vector<glm::vec3> actual = solver.read_distances();
    std::size_t mismatches = 0;
    float worst = 0.0f, worst_cpu_field = 0.0f;
    for (std::size_t i = 0; i < labels.size(); ++i)
      for (int band = 0; band < 3; ++band) {
        float e = expected[i][band], a = actual[i][band];
        if ((e < kUnreached) != (a < kUnreached)) {
          ++mismatches;
          continue;
        }
        if (e >= kUnreached) continue;
        float error = std::abs(a - e) / std::max(e, 1e-3f);
        worst = std::max(worst, error);
        worst_cpu_field = std::max(worst_cpu_field, std::abs(a - from_cpu_field[i][band]) / std::max(e, 1e-3f));
        if (error > 1e-5f) ++mismatches;
      }
    fmt::print("{}: coefficient (green) {:.2f}..{:.2f} per unit, {} of {} bands off the CPU field by more than the bound "
               "(worst {:.2e}), {} sweeps, worst relative difference to Dijkstra {:.2e} (on the CPU field {:.2e})\n",
               c.name, lowest, highest, field_mismatches, bands, worst_field, stats.iterations, worst, worst_cpu_field);
    EXPECT_EQ(mismatches, 0u) << c.name << ", worst " << worst;
    EXPECT_LT(worst_cpu_field, 1e-3f) << c.name;
  }
}

INSTANTIATE_TEST_SUITE_P(VoxelPaths, Relaxation,
                         ::testing::Values(RelaxationSchedule::kSweep, RelaxationSchedule::kActiveBlocks),
                         [](const ::testing::TestParamInfo<RelaxationSchedule>& schedule) {
                           return schedule.param == RelaxationSchedule::kSweep ? std::string("Sweep") : std::string("ActiveBlocks");
                         });

// The side-lit sphere with marble veins and with skin-like layers (scale_mm 0.4, contrast 20) against
// the homogeneous one (R = 32): the denser matter darkens the image (mean green lower) and pixels change: mean
// relative difference measured 0.047 for marble (thin veins: shortest paths mostly go around them, and the lit
// side's voxels keep their own n0) and 0.81 for layered (the dense outer layer is on every path); asserted > 0.02.
TEST(VoxelPaths, HeterogeneousFieldsChangeTheRender) {
  lucent::test::ensure_gl_context();
  auto render = [](const std::string& field) {
    lucent::Scene scene = side_lit_sphere(
        R"({"name": "voxel-paths", "resolution": 32, "light_map_size": 256, "specular": false})");
    lucent::MediumField& f = scene.objects[0].material->field;  // scale_mm 1: mm = scene units
    f.type = field == "marble" ? lucent::MediumFieldType::Marble
             : field == "layered" ? lucent::MediumFieldType::Layered
                                  : lucent::MediumFieldType::None;
    f.scale_mm = 0.4f, f.contrast = 20.0f;
    lucent::OffscreenFramebuffer framebuffer(64, 64);
    lucent::Renderer renderer(scene);
    renderer.render(scene.camera, {framebuffer.id(), 64, 64});
    return renderer.read_radiance();
  };
  const lucent::ImageRGBA32F homogeneous = render("none");
  for (const char* field : {"marble", "layered"}) {
    const lucent::ImageRGBA32F image = render(field);
    double sum_h = 0.0, sum_f = 0.0, sum_difference = 0.0;
    int covered = 0;
    for (std::size_t i = 0; i < 64 * 64; ++i) {
      const float* a = &homogeneous.pixels[4 * i];
      const float* b = &image.pixels[4 * i];
      ASSERT_TRUE(std::isfinite(b[0]) && std::isfinite(b[1]) && std::isfinite(b[2]));
      if (a[3] <= 0.0f) continue;
      sum_h += a[1], sum_f += b[1], ++covered;
      sum_difference += std::abs(b[1] - a[1]) / std::max(a[1], 1e-6f);
    }
    ASSERT_GT(covered, 0);
    const double mean_difference = sum_difference / covered;
    fmt::print("{}: mean green {:.4f} (homogeneous {:.4f}), mean relative pixel difference {:.3f}\n", field,
               sum_f / covered, sum_h / covered, mean_difference);
    EXPECT_LT(sum_f, sum_h) << field;
    EXPECT_GT(mean_difference, 0.02) << field;
  }
}

// Point light vs directional light: the side-lit sphere (r = 1, scale_mm 1) lit by a point light at (10, 0, 0)
// of intensity I = 1e-4 W/sr (1e2 per scene unit^2: irradiance I / d^2 = 1 at the sphere's centre) against the
// directional light of radiance 1 from the same direction (R = 32, light maps 256). The mean green radiance over
// the covered pixels agrees within 15%: the point light's irradiance I cos / d^2 varies over the lit half (d from
// 9 at the nearest point to ~9.95 at the limb: 1.23 to 1.01 times the centre's), and its diverging rays light a
// cap slightly smaller than a hemisphere (up to 84 degrees from the axis instead of 90), so the two are not the
// same image; the measured difference is stated in docs/methods/voxel-paths.md. The point light's image is also
// brighter on its side (x > 40 pixels) than on the far side (x < 24), as the directional one is.
TEST(VoxelPaths, PointLightScattersLikeTheEquivalentDirectionalLight) {
  lucent::test::ensure_gl_context();
  auto render = [](const std::string& light) {
    lucent::Scene scene = lucent::parse_scene(fmt::format(R"({{
    "scale_mm": 1,
    "camera": {{ "eye": [0, 0, 6], "target": [0, 0, 0], "fov_y_deg": 22 }},
    "lights": [{}],
    "objects": [{{ "shape": "sphere", "radius": 1, "segments": 96,
                  "material": {{ "sigma_a": [0.01, 0.02, 0.04], "sigma_s": [0.5, 0.6, 0.7], "g": 0 }} }}],
    "method": {{"name": "voxel-paths", "resolution": 32, "light_map_size": 256, "specular": false}},
    "render": {{ "width": 64, "height": 64, "frames": 1 }} }})",
                                                          light),
                                              "point-lit sphere", ".");
    lucent::OffscreenFramebuffer framebuffer(64, 64);
    lucent::Renderer renderer(scene);
    renderer.render(scene.camera, {framebuffer.id(), 64, 64});
    return renderer.read_radiance();
  };
  struct Means {
    double all = 0.0, lit = 0.0, dark = 0.0;
  };
  auto means = [](const lucent::ImageRGBA32F& image) {
    Means m;
    int n = 0, lit_n = 0, dark_n = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const float* p = &image.pixels[(static_cast<std::size_t>(y) * 64 + static_cast<std::size_t>(x)) * 4];
        EXPECT_TRUE(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
        if (p[3] <= 0.0f) continue;
        m.all += p[1], ++n;
        if (x > 40) m.lit += p[1], ++lit_n;
        if (x < 24) m.dark += p[1], ++dark_n;
      }
    EXPECT_GT(n, 0);
    m.all /= std::max(n, 1), m.lit /= std::max(lit_n, 1), m.dark /= std::max(dark_n, 1);
    return m;
  };
  const Means directional = means(render(R"({ "direction": [-1, 0, 0], "radiance": [1, 1, 1] })"));
  EXPECT_GT(directional.all, 0.05);
  // d = 10 (tolerance 15%) and d = 40 (I = 16e-4: the same irradiance at the centre; rays nearly parallel, the
  // irradiance varies by +-5% over the sphere, about +3.4% on average over the lit half (2 <x> / d, <x> ~ 0.67):
  // tolerance 5%). Measured 1.114 and 1.035: the difference shrinks as 1 / d, as it should.
  for (auto [distance, tolerance] : {std::pair{10.0, 0.15}, std::pair{40.0, 0.05}}) {
    const double intensity = 1e-6 * distance * distance;
    const Means point = means(render(fmt::format(R"({{ "type": "point", "position": [{}, 0, 0], "intensity": [{}, {}, {}] }})",
                                                 distance, intensity, intensity, intensity)));
    fmt::print("directional: mean green {:.4f} (lit side {:.4f}, far side {:.4f}); point at d = {}: {:.4f} ({:.4f}, "
               "{:.4f}); point / directional {:.3f}\n",
               directional.all, directional.lit, directional.dark, distance, point.all, point.lit, point.dark,
               point.all / directional.all);
    EXPECT_NEAR(point.all / directional.all, 1.0, tolerance) << "d = " << distance;
    EXPECT_GT(point.lit, 1.5 * point.dark) << "d = " << distance;
    if (distance != 10.0) continue;
    // A spot light on the same axis whose inner cone (30 degrees) contains the whole sphere (5.7 degrees): the
    // same image (the cone factor is exactly 1 and the G-buffer frustum the same; tolerance 1e-3, measured equal).
    const Means spot = means(render(fmt::format(
        R"({{ "type": "spot", "position": [{}, 0, 0], "direction": [-1, 0, 0], "inner_deg": 30, "outer_deg": 40,
             "intensity": [{}, {}, {}] }})",
        distance, intensity, intensity, intensity)));
    fmt::print("spot at d = {}: mean green {:.4f}, spot / point {:.5f}\n", distance, spot.all, spot.all / point.all);
    EXPECT_NEAR(spot.all / point.all, 1.0, 1e-3);
  }
}

// Cube-face layers: a point light at the origin between two spheres (r = 1, centres x = +-3) lies inside the
// translucent objects' bounding sphere, so its G-buffer is 6 cube faces; the sphere at +3 must come out as when
// it is alone and the same light sees it through one frustum (half-angle 19.9 degrees). Same voxel size 0.125 on
// voxel-aligned grids (R = 68 and R = 20): the image depends on the grid's placement by up to +-8% (eq. 3's
// per-voxel binning: measured 0.336 to 0.387 for R = 18..24 alone), so the grids must match. And the same texel
// size on the sphere: light maps 704 (cube, 90 degrees) and 256 (frustum), ~0.0028 units at distance 2. With 256
// for both the cube's 2.8x wider texels gave 1.060: coarser texels make the per-voxel flux noisier, and the
// shortest path (a minimum over sources) picks up the upward fluctuations. Measured ratio 0.994; tolerance 3%.
// A wrong solid angle (tan(a) vs a: 1.62x on a cube face) would be far outside.
TEST(VoxelPaths, PointLightCubeFacesScatterLikeItsFrustum) {
  lucent::test::ensure_gl_context();
  auto render = [](const std::string& objects, int resolution, int map_size) {
    lucent::Scene scene = lucent::parse_scene(fmt::format(R"({{
    "scale_mm": 1,
    "camera": {{ "eye": [3, 0, 8], "target": [3, 0, 0], "fov_y_deg": 22 }},
    "lights": [{{ "type": "point", "position": [0, 0, 0], "intensity": [9e-6, 9e-6, 9e-6] }}],
    "objects": [{}],
    "method": {{"name": "voxel-paths", "resolution": {}, "light_map_size": {}, "specular": false}},
    "render": {{ "width": 64, "height": 64, "frames": 1 }} }})",
                                                          objects, resolution, map_size),
                                              "point-lit spheres", ".");
    EXPECT_EQ(scene.point_lights.size(), 1u);
    lucent::OffscreenFramebuffer framebuffer(64, 64);
    lucent::Renderer renderer(scene);
    renderer.render(scene.camera, {framebuffer.id(), 64, 64});
    const lucent::ImageRGBA32F image = renderer.read_radiance();
    double sum = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < 64 * 64; ++i) {
      const float* p = &image.pixels[4 * i];
      EXPECT_TRUE(std::isfinite(p[1]));
      if (p[3] > 0.0f) sum += p[1], ++n;
    }
    EXPECT_GT(n, 0);
    return sum / std::max(n, 1);
  };
  const std::string sphere = R"({ "shape": "sphere", "radius": 1, "segments": 96, "translate": [3, 0, 0],
    "material": { "sigma_a": [0.01, 0.02, 0.04], "sigma_s": [0.5, 0.6, 0.7], "g": 0 } })";
  const std::string other = R"({ "shape": "sphere", "radius": 1, "segments": 96, "translate": [-3, 0, 0],
    "material": { "sigma_a": [0.01, 0.02, 0.04], "sigma_s": [0.5, 0.6, 0.7], "g": 0 } })";
  const double frustum = render(sphere, 20, 256);
  const double cube = render(sphere + ", " + other, 68, 704);
  fmt::print("sphere at +3, light at 0: mean green {:.4f} (frustum layer), {:.4f} (cube faces), ratio {:.3f}\n",
             frustum, cube, cube / frustum);
  EXPECT_GT(frustum, 0.02);
  EXPECT_NEAR(cube / frustum, 1.0, 0.03);
}

}  // namespace

namespace {

// Deforming objects: voxel-paths voxelizes the renderer's own vertex buffer, which SceneGpu deforms every frame.
// The labels from it at time t equal, voxel for voxel, those of the CPU triangles of scene_at_time(t) (the same
// deformation code, so the same float positions), and the labels at two instants differ.
TEST(VoxelPaths, DeformingObjectVoxelizesAsItIsThisFrame) {
  lucent::test::ensure_gl_context();
  const lucent::Scene scene = lucent::load_scene(std::string(LUCENT_SCENES_DIR) + "/deforming_inclusion.json");
  lucent::render::SceneGpu scene_gpu(scene);
  TriangleSource source{scene_gpu.vertex_buffer(), scene_gpu.index_buffer(), {}};
  for (const auto& mesh : scene_gpu.translucent_meshes())
    source.objects.push_back({mesh.first_index, mesh.index_count, mesh.object + 1});
  ASSERT_EQ(source.objects.size(), 1u);
  const VoxelGrid grid = grid_around(scene_gpu.translucent_lower(), scene_gpu.translucent_upper(), 48, 2);
  Voxelizer voxelizer;
  std::vector<std::vector<std::uint32_t>> at_time;
  for (double t : {0.0, 0.75}) {
    scene_gpu.update(t, nullptr);
    voxelizer.voxelize(source, grid);
    at_time.push_back(voxelizer.read_labels());
    voxelizer.voxelize(gather_translucent_triangles(lucent::scene_at_time(scene, t)), grid);
    const std::vector<std::uint32_t> cpu = voxelizer.read_labels();
    std::size_t different = 0;
    for (std::size_t i = 0; i < cpu.size(); ++i) different += cpu[i] != at_time.back()[i] ? 1 : 0;
    fmt::print("t = {}: {} voxels inside, {} differ from the CPU triangles of scene_at_time\n", t,
               inside_count(at_time.back()), different);
    EXPECT_EQ(different, 0u) << "t = " << t;
    EXPECT_GT(inside_count(at_time.back()), 1000u);
  }
  std::size_t moved = 0;
  for (std::size_t i = 0; i < at_time[0].size(); ++i) moved += at_time[0][i] != at_time[1][i] ? 1 : 0;
  fmt::print("{} voxels change between t = 0 and t = 0.75 s\n", moved);
  EXPECT_GT(moved, inside_count(at_time[0]) / 20);
}

}  // namespace

namespace {

// Camera moves reuse the solved radiance volume: the second frame of a renderer whose camera moved runs only the
// shading pass (no relax step in its timings) and gives the same image, bit for bit, as a fresh renderer that
// solves for the moved camera; Renderer::restart() and a time change of an animated scene solve again.
TEST(VoxelPaths, CameraMovesReuseTheSolvedVolume) {
  lucent::test::ensure_gl_context();
  lucent::Scene scene = side_lit_sphere(R"({"name": "voxel-paths", "resolution": 32, "light_map_size": 256})");
  lucent::Camera moved = scene.camera;
  moved.eye = glm::vec3(2.0f, 1.0f, 5.5f);
  lucent::OffscreenFramebuffer framebuffer(64, 64);
  auto has_relax = [](lucent::Renderer& r) {
    for (const lucent::PassTiming& step : r.last_frame_timings().passes)
      if (step.name == "relax") return true;
    return false;
  };
  lucent::Renderer reused(scene);
  reused.render(scene.camera, {framebuffer.id(), 64, 64});
  EXPECT_TRUE(has_relax(reused));
  reused.render(moved, {framebuffer.id(), 64, 64});
  EXPECT_FALSE(has_relax(reused));
  const lucent::ImageRGBA32F second = reused.read_radiance();
  lucent::Renderer fresh(scene);
  fresh.render(moved, {framebuffer.id(), 64, 64});
  const lucent::ImageRGBA32F expected = fresh.read_radiance();
  ASSERT_EQ(second.pixels.size(), expected.pixels.size());
  std::size_t different = 0;
  for (std::size_t i = 0; i < expected.pixels.size(); ++i) different += second.pixels[i] != expected.pixels[i] ? 1 : 0;
  EXPECT_EQ(different, 0u);
  reused.restart();  // Renderer::restart: recompute everything next frame (the benchmarks' per-frame cost)
  reused.render(moved, {framebuffer.id(), 64, 64});
  EXPECT_TRUE(has_relax(reused));

  lucent::Scene animated = lucent::load_scene(std::string(LUCENT_SCENES_DIR) + "/deforming_inclusion.json",
                                              {"method.resolution=32", "method.light_map_size=128"});
  lucent::Renderer r(animated);
  r.render(animated.camera, {framebuffer.id(), 64, 64});
  r.set_time(0.5);
  r.render(animated.camera, {framebuffer.id(), 64, 64});
  EXPECT_TRUE(has_relax(r));
}

}  // namespace

namespace {

// entry_depth d: every lit voxel of a homogeneous object starts d h sigma_t later, so every shortest path, and
// hence every pixel, is darker by exactly exp(-d h sigma_t) per band (up to the RGBA16F radiance texture's
// rounding, 2^-11 relative per value: tolerance 3e-3 on the ratio).
TEST(VoxelPaths, EntryDepthDarkensEveryPixelByItsTransmittance) {
  lucent::test::ensure_gl_context();
  auto render = [](double entry_depth) {
    lucent::Scene scene = side_lit_sphere(fmt::format(
        R"({{"name": "voxel-paths", "resolution": 32, "light_map_size": 256, "specular": false, "entry_depth": {}}})",
        entry_depth));
    lucent::OffscreenFramebuffer framebuffer(64, 64);
    lucent::Renderer renderer(scene);
    renderer.render(scene.camera, {framebuffer.id(), 64, 64});
    return renderer.read_radiance();
  };
  const lucent::ImageRGBA32F base = render(0.0), deeper = render(1.0);
  const lucent::Scene scene = side_lit_sphere(R"({"name": "voxel-paths"})");
  const TranslucentTriangles triangles = gather_translucent_triangles(scene);
  const VoxelGrid grid = grid_around(triangles.lower, triangles.upper, 32, 2);
  const glm::vec3 sigma_t = scene.objects[0].material->sigma_t() * scene.scale_mm;
  int covered = 0;
  float worst = 0.0f;
  for (std::size_t i = 0; i < 64 * 64; ++i) {
    if (base.pixels[4 * i + 3] <= 0.0f) continue;
    for (int band = 0; band < 3; ++band) {
      const float a = base.pixels[4 * i + static_cast<std::size_t>(band)];
      if (a < 1e-3f) continue;
      const float expected = std::exp(-grid.voxel_size * sigma_t[band]);
      worst = std::max(worst, std::abs(deeper.pixels[4 * i + static_cast<std::size_t>(band)] / a - expected) / expected);
    }
    ++covered;
  }
  fmt::print("{} covered pixels, h = {:.4f}, worst relative deviation from exp(-h sigma_t) {:.2e}\n", covered,
             grid.voxel_size, worst);
  ASSERT_GT(covered, 500);
  EXPECT_LT(worst, 3e-3f);
}

}  // namespace
