// test_blob_isosurface.cpp: the GPU blob isosurface on llvmpipe (48-cell grid): (a-c) every test frame is
// watertight, consistently oriented, of the right volume and topology, with normals that agree with the faces;
// (d) it equals the CPU reference; (e) consecutive frames differ; the indirect draw draws what was extracted;
// too small a capacity is an error. Timings for docs/methods/blob-isosurface.md: DISABLED_ExtractionTimes.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <vector>

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "../blob_surface_checks.h"
#include "geometry/blob_isosurface.h"
#include "geometry/isosurface_cpu.h"
#include "gpu/frame_profiler.h"
#include "gpu/shader_program.h"
#include "image_compare.h"
#include "lucent/error.h"
#include "lucent/offscreen_framebuffer.h"

namespace {

using lucent::TriangleMesh;
using lucent::geometry::BlobIsosurface;
using lucent::geometry::IsosurfaceGrid;

constexpr int kObjectIndex = 3;

struct Comparison {
  std::size_t sign_flips = 0;    // grid samples whose inside/outside differs between GPU and CPU
  float max_sample_difference = 0.0f;
  float max_position_difference = 0.0f;  // [scene units]
  float min_normal_dot = 1.0f;
};

// GPU vs CPU, vertex by vertex and index by index (both emit in grid order, so no sorting is needed).
void expect_same_mesh(const TriangleMesh& gpu, const TriangleMesh& cpu, Comparison* c) {
  ASSERT_EQ(gpu.positions.size(), cpu.positions.size());
  ASSERT_EQ(gpu.indices.size(), cpu.indices.size());
  EXPECT_TRUE(gpu.indices == cpu.indices) << "same counts, different triangles";
  for (std::size_t v = 0; v < gpu.positions.size(); ++v) {
    c->max_position_difference = std::max(c->max_position_difference, glm::length(gpu.positions[v] - cpu.positions[v]));
    c->min_normal_dot = std::min(c->min_normal_dot, glm::dot(gpu.normals[v], cpu.normals[v]));
  }
  // Tolerance: float32 exp/sin on the GPU vs libm move a sample by ~1e-7, a vertex by ~1e-6 units.
  EXPECT_LT(c->max_position_difference, 1e-4f);
  EXPECT_GT(c->min_normal_dot, 0.9999f);
}

TEST(BlobIsosurfaceGpu, FramesAreWatertightOrientedAndEqualTheCpuReference) {
  lucent::test::ensure_gl_context();
  IsosurfaceGrid grid = lucent::geometry::blob_grid(48);
  BlobIsosurface surface(grid, kObjectIndex);
  std::ofstream csv(lucent::test::output_path("blob_isosurface_frames.csv"));
  csv << "time_s,vertices,triangles,components,euler,volume,counted_volume,min_area_over_h2,mean_normal_dot,"
         "sign_flips,max_sample_difference,max_position_difference\n";
  for (const lucent::test::BlobFrame& frame : lucent::test::blob_test_frames()) {
    SCOPED_TRACE(fmt::format("t = {} s", frame.time));
    surface.extract(frame.time);
    TriangleMesh gpu = surface.read_mesh();
    std::vector<float> gpu_samples = surface.read_samples();

    // (a)-(c), (f): closed, oriented, volume, normals, one sphere per body.
    lucent::test::SurfaceMeasures m = lucent::test::measure_surface(gpu, grid, gpu_samples);
    lucent::test::expect_closed_oriented_surface(m);
    EXPECT_EQ(m.topology.components, frame.bodies);
    for (const lucent::shader::VertexGPU& v : surface.read_vertices()) ASSERT_EQ(v.position.w, kObjectIndex);

    // (d): the CPU reference. Where GPU and CPU samples straddle zero differently (possible, rare: float32
    // transcendental functions differ by an ulp or two), the extraction itself is compared on the GPU's samples.
    std::vector<float> cpu_samples = lucent::geometry::sample_blob_field(grid, frame.time);
    Comparison c;
    for (std::size_t i = 0; i < cpu_samples.size(); ++i) {
      c.max_sample_difference = std::max(c.max_sample_difference, std::abs(gpu_samples[i] - cpu_samples[i]));
      c.sign_flips += (gpu_samples[i] > 0.0f) != (cpu_samples[i] > 0.0f) ? 1 : 0;
    }
    EXPECT_LT(c.max_sample_difference, 1e-5f);
    EXPECT_LE(c.sign_flips, cpu_samples.size() / 10000) << "GPU and CPU fields disagree on inside/outside";
    const std::vector<float>& reference_samples = c.sign_flips == 0 ? cpu_samples : gpu_samples;
    expect_same_mesh(gpu, lucent::geometry::extract_blob_isosurface(grid, reference_samples, frame.time), &c);
    csv << fmt::format("{},{},{},{},{},{:.6f},{:.6f},{:.4g},{:.6f},{},{:.3g},{:.3g}\n", frame.time,
                       m.topology.vertices, m.topology.triangles, m.topology.components, m.topology.euler(),
                       m.volume, m.counted_volume, m.min_area_over_h2, m.mean_normal_dot, c.sign_flips,
                       c.max_sample_difference, c.max_position_difference);
  }
}

// (e): frames 1/60 s apart are different surfaces: vertices move by a measurable fraction of a cell.
TEST(BlobIsosurfaceGpu, ConsecutiveFramesDiffer) {
  lucent::test::ensure_gl_context();
  IsosurfaceGrid grid = lucent::geometry::blob_grid(48);
  BlobIsosurface surface(grid, 0);
  const float dt = 1.0f / 60.0f;
  for (float t : {0.5f, 6.2f, 20.0f}) {
    SCOPED_TRACE(fmt::format("t = {} s", t));
    surface.extract(t);
    TriangleMesh a = surface.read_mesh();
    surface.extract(t + dt);
    TriangleMesh b = surface.read_mesh();
    // The first frame's vertices are on its surface; on the next frame's field they are off it by about
    // |f| / |grad f|, the surface's displacement in 1/60 s (measured mean: 0.0023-0.0031 units, a 20th of a
    // cell; the interpolation's own offset from the surface cancels, being the same in both frames).
    double moved = 0.0;
    for (const glm::vec3& p : a.positions)
      moved += std::abs(lucent::shader::blob_field(p, t + dt)) /
               glm::length(lucent::shader::blob_field_gradient(p, t + dt));
    moved /= static_cast<double>(a.positions.size());
    RecordProperty(fmt::format("mean_displacement_t{}", t), std::to_string(moved));
    EXPECT_GT(moved, 1e-3) << "the surface did not move";
    EXPECT_TRUE(a.positions != b.positions) << "identical vertex positions in consecutive frames";
  }
}

// The indirect draw issues exactly the extracted triangles and covers the body's silhouette.
TEST(BlobIsosurfaceGpu, IndirectDrawDrawsTheExtractedTriangles) {
  lucent::test::ensure_gl_context();
  BlobIsosurface surface(lucent::geometry::blob_grid(48), 0);
  surface.extract(6.25f);
  std::uint32_t triangles = surface.read_counts().triangles;

  const int size = 64;
  lucent::OffscreenFramebuffer framebuffer(size, size);
  auto program = lucent::gpu::ShaderProgram::graphics("tests/isosurface_draw.vert", "", "tests/isosurface_draw.frag");
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
  glViewport(0, 0, size, size);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program.id());
  GLuint query = 0;
  glCreateQueries(GL_PRIMITIVES_GENERATED, 1, &query);
  glBeginQuery(GL_PRIMITIVES_GENERATED, query);
  surface.draw();
  glEndQuery(GL_PRIMITIVES_GENERATED);
  GLuint64 primitives = 0;
  glGetQueryObjectui64v(query, GL_QUERY_RESULT, &primitives);
  glDeleteQueries(1, &query);
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(size * size * 4));
  glReadPixels(0, 0, size, size, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);

  EXPECT_EQ(primitives, triangles);
  std::size_t covered = 0;
  for (std::size_t i = 3; i < pixels.size(); i += 4) covered += pixels[i] > 0 ? 1 : 0;
  // The merged body seen along z spans about 2 x 1 units of the 4 x 4 view: roughly 10% of the pixels.
  EXPECT_GT(covered, static_cast<std::size_t>(size * size) / 20);
  EXPECT_LT(covered, static_cast<std::size_t>(size * size) / 3);
}

TEST(BlobIsosurfaceGpu, OverCapacityIsAnErrorAndDrawsNothing) {
  lucent::test::ensure_gl_context();
  BlobIsosurface surface(lucent::geometry::blob_grid(32), 0, 1000);
  surface.extract(1.0f);
  try {
    surface.read_counts();
    FAIL() << "no error for a surface of more than 1000 triangles";
  } catch (const lucent::Error& e) {
    EXPECT_NE(std::string(e.what()).find("capacity of 1000"), std::string::npos) << e.what();
  }
  lucent::shader::DrawElementsIndirectGPU command{};
  glGetNamedBufferSubData(surface.indirect_buffer(), 0, sizeof(command), &command);
  EXPECT_EQ(command.count, 0u);
  glFinish();
  EXPECT_THROW(surface.extract(2.0f), lucent::Error) << "extract() should report the earlier overflow";
}

TEST(BlobIsosurfaceGpu, BadGridIsAnError) {
  lucent::test::ensure_gl_context();
  IsosurfaceGrid grid = lucent::geometry::blob_grid(32);
  grid.cells.y = 1;
  EXPECT_THROW(BlobIsosurface(grid, 0), lucent::Error);
}

// Timings for the doc (no assertions): run with
//   build-blob/tests/lucent_gl_tests --gtest_also_run_disabled_tests --gtest_filter='*ExtractionTimes*'
TEST(BlobIsosurfaceGpu, DISABLED_ExtractionTimes) {
  lucent::test::ensure_gl_context();
  std::ofstream csv(lucent::test::output_path("blob_isosurface_times.csv"));
  csv << "resolution,cells,triangles,vertices,gpu_memory_mib,wall_ms_median,cpu_reference_ms_median,pass,"
         "gpu_ms_median\n";
  for (int resolution : {32, 48, 64, 128}) {
    IsosurfaceGrid grid = lucent::geometry::blob_grid(resolution);
    BlobIsosurface surface(grid, 0);
    lucent::gpu::FrameProfiler profiler;
    std::vector<double> wall;
    std::vector<std::vector<std::pair<std::string, double>>> passes;
    std::uint32_t triangles = 0, vertices = 0;
    for (int frame = 0; frame < 12; ++frame) {
      float t = 0.25f * static_cast<float>(frame);
      glFinish();
      auto start = std::chrono::steady_clock::now();
      profiler.begin_frame(static_cast<std::uint64_t>(frame) + 1);
      surface.extract(t, &profiler);
      profiler.end_frame();
      glFinish();
      double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      auto counts = surface.read_counts();
      triangles = std::max(triangles, counts.triangles);
      vertices = std::max(vertices, counts.vertices);
      if (frame < 2) continue;  // warm-up: shader compilation in the driver, first-touch of buffers
      wall.push_back(ms);
      passes.push_back(profiler.collect(/*wait=*/true).back().passes);
    }
    auto median = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    std::vector<double> cpu;
    for (int frame = 0; frame < 3; ++frame) {
      auto start = std::chrono::steady_clock::now();
      lucent::geometry::extract_blob_isosurface(grid, 0.25f * static_cast<float>(frame));
      cpu.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::string cells = fmt::format("{}x{}x{}", grid.cells.x, grid.cells.y, grid.cells.z);
    double mib = static_cast<double>(surface.gpu_memory_bytes()) / (1024.0 * 1024.0);
    for (std::size_t p = 0; p < passes[0].size(); ++p) {
      std::vector<double> times;
      for (const auto& frame : passes) times.push_back(frame[p].second);
      std::string line = fmt::format("{},{},{},{},{:.1f},{:.2f},{:.2f},{},{:.3f}", resolution, cells, triangles,
                                     vertices, mib, median(wall), median(cpu), passes[0][p].first, median(times));
      csv << line << "\n";
      std::printf("%s\n", line.c_str());
    }
  }
}

}  // namespace
