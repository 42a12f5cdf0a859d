// test_thickness_field.cpp: the multipole model's thickness per surface point on the GPU.
//   - The shaders' lookup (geometry/thickness_field.h compiled as GLSL) reads a packed grid as the C++ lookup does,
//     at points on, inside and outside the surface, with the grid placed after other texels in the buffer.
//   - Every diffusion method that evaluates S_d at a shading point reads its object's grid there: a slab whose grid
//     holds one thickness everywhere renders as the slab whose material states that thickness, and unlike the same
//     slab at its measured thickness (the median, which the material keeps).
#include <cmath>
#include <utility>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "geometry/thickness_grid.h"
#include "image_compare.h"
#include "lucent/lucent.h"
#include "temp_cache_dir.h"

namespace {

const char* kMain = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 1) readonly buffer Points { vec4 points[]; };  // xyz; w: the grid's first texel
layout(std430, binding = 2) writeonly buffer Results { float results[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(points.length())) return;
  results[i] = thickness_at(int(points[i].w), points[i].xyz);
}
)";

TEST(ThicknessField, ComputeShaderReadsTheGridAsCpp) {
  lucent::test::ensure_gl_context();
  const lucent::TriangleMesh sphere = lucent::make_sphere(1.0f, 24, 48);
  std::vector<double> values(sphere.indices.size() / 3);
  for (std::size_t t = 0; t < values.size(); ++t) {
    const glm::vec3 c = sphere.positions[sphere.indices[3 * t]];
    values[t] = 2.0 + static_cast<double>(c.x) + 0.5 * static_cast<double>(c.y * c.z);  // not separable per axis
  }
  const lucent::ThicknessGrid grid = lucent::thickness_grid(sphere, values, 7.0, 20);
  std::vector<glm::vec4> texels(5, glm::vec4(-1.0f));  // other data before the grid
  const int first = lucent::append_thickness_grid(grid, texels);

  std::string source = "#version 450 core\n" + lucent::test::embedded_without_includes("shared/bridge.h") +
                       "layout(std430, binding = 0) readonly buffer Texels { vec4 material_map_texels[]; };\n"
                       "#define LUCENT_THICKNESS_FIELDS 1\n" +
                       lucent::test::embedded_without_includes("geometry/thickness_field.h");
  const GLuint program = lucent::test::compile_compute_source(source + kMain);
  ASSERT_NE(program, 0u);

  std::vector<glm::vec4> points;
  for (int k = 0; k < 256; ++k) {  // on the surface, just inside and outside it, deep inside, beyond the grid
    const float z = 1.0f - (2.0f * static_cast<float>(k) + 1.0f) / 256.0f, phi = 2.39996f * static_cast<float>(k);
    const float r = std::sqrt(1.0f - z * z);
    const float radius = k % 5 == 0 ? 0.97f : k % 5 == 1 ? 1.03f : k % 5 == 2 ? 0.3f : k % 5 == 3 ? 1.5f : 1.0f;
    points.emplace_back(radius * glm::vec3(r * std::cos(phi), r * std::sin(phi), z), static_cast<float>(first));
  }
  std::vector<float> gpu(points.size());
  GLuint buffers[3];
  glCreateBuffers(3, buffers);
  glNamedBufferStorage(buffers[0], static_cast<GLsizeiptr>(texels.size() * sizeof(glm::vec4)), texels.data(), 0);
  glNamedBufferStorage(buffers[1], static_cast<GLsizeiptr>(points.size() * sizeof(glm::vec4)), points.data(), 0);
  glNamedBufferStorage(buffers[2], static_cast<GLsizeiptr>(gpu.size() * sizeof(float)), nullptr, 0);
  glUseProgram(program);
  for (GLuint b = 0; b < 3; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers[b]);
  glDispatchCompute(static_cast<GLuint>((points.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffers[2], 0, static_cast<GLsizeiptr>(gpu.size() * sizeof(float)), gpu.data());
  glDeleteBuffers(3, buffers);
  glDeleteProgram(program);

  int fallbacks = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const float cpu = lucent::thickness_at(grid, glm::vec3(points[i]));
    fallbacks += cpu == 7.0f;
    EXPECT_NEAR(gpu[i], cpu, 1e-5f * cpu) << "point " << i;
  }
  EXPECT_GT(fallbacks, 50);  // deep inside and beyond the grid
  EXPECT_LT(fallbacks, 130);
}

// A front-lit slab 2 x 2 x 0.2 scene units (2 mm thick at 10 mm per unit) in a medium whose reflectance depends on
// the thickness (reduced albedo 0.99, 1 mm mean free path), seen straight on at 16 x 16 pixels, 2 frames.
lucent::Scene slab_scene(const std::string& method, const std::string& thickness) {
  const std::string json = fmt::format(R"({{
    "scale_mm": 10,
    "camera": {{ "eye": [0, 0, 3], "target": [0, 0, 0], "fov_y_deg": 20 }},
    "lights": [{{ "direction": [0.3, -0.2, -0.93], "radiance": [2, 2, 2] }}],
    "objects": [{{ "shape": "box", "size": [2, 2, 0.2],
                  "material": {{ "sigma_a": [0.01, 0.01, 0.01], "sigma_s": [0.99, 0.99, 0.99], "g": 0, "eta": 1.3,
                                "model": "multipole", {} }} }}],
    "method": {},
    "render": {{ "width": 16, "height": 16, "frames": 2, "seed": 3 }} }})",
                                       thickness, method);
  return lucent::parse_scene(json, "thickness slab", ".");
}

lucent::ImageRGBA32F render(const lucent::Scene& scene) {
  lucent::OffscreenFramebuffer framebuffer(16, 16);
  lucent::Renderer renderer(scene);
  for (int f = 0; f < 2; ++f) renderer.render(scene.camera, {framebuffer.id(), 16, 16});
  return renderer.read_radiance();
}

double mean_abs_difference(const lucent::ImageRGBA32F& a, const lucent::ImageRGBA32F& b, double& mean) {
  double sum = 0.0, level = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    if (i % 4 != 3) sum += std::abs(a.pixels[i] - b.pixels[i]), level += b.pixels[i];
  mean = level / static_cast<double>(a.pixels.size() * 3 / 4);
  return sum / static_cast<double>(a.pixels.size() * 3 / 4);
}

// radiosity-maps evaluates S_d through the same function as per-pixel (common/light_sampling.glsl). Hybrid's local
// pattern keeps the strata of the material's thickness (another sampling of the same integral): its renders agree
// within 6% per pixel on average, not to rounding.
TEST(ThicknessField, DiffusionMethodsReadTheGridWhereTheyShade) {
  lucent::test::ensure_gl_context();
  lucent::test::TempCacheDir cache;
  bool first = true;
  for (const auto& [method, tolerance] : {std::pair{R"({"name": "per-pixel", "N": 32, "specular": false})", 1e-4},
                                          std::pair{R"({"name": "hybrid", "specular": false})", 0.06},
                                          std::pair{R"({"name": "texture-space-is", "specular": false})", 1e-4}}) {
    lucent::Scene measured = slab_scene(method, R"("thickness_from_mesh": true)");
    ASSERT_FALSE(measured.objects[0].thickness.empty());
    const lucent::ImageRGBA32F stated = render(slab_scene(method, R"("thickness_mm": 0.5)"));
    double level = 0.0;
    if (first) {  // the thickness matters: the measured grid (2 mm) renders far from 0.5 mm
      const double apart = mean_abs_difference(render(measured), stated, level);
      std::printf("the slab at its measured thickness against 0.5 mm: %.2e (mean radiance %.4f)\n", apart, level);
      EXPECT_GT(apart, 0.5 * level);
      first = false;
    }
    // The grid set to 0.5 mm everywhere (0.05 scene units), the material still at the median (2 mm).
    for (float& value : measured.objects[0].thickness.values)
      if (value > 0.0f) value = 0.05f;
    measured.objects[0].thickness.fallback = 0.05f;
    const double same = mean_abs_difference(render(measured), stated, level);
    std::printf("%s: the grid at 0.5 mm against the material at 0.5 mm: %.2e (mean radiance %.4f)\n", method, same,
                level);
    EXPECT_LT(same, tolerance * level) << method;
  }
}

}  // namespace
