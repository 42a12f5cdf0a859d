// test_equirect_glsl.cpp: the equirectangular mapping (lights/equirect.h) is embedded for the shaders, compiles
// as GLSL 4.50 and gives the same (u, v), directions and pixel solid angles in a compute shader as in C++.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "gpu/shader_sources.h"
#include "image_compare.h"
#include "lights/equirect.h"
#include "lucent/environment.h"

namespace {

const char* kMain = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Directions { vec4 directions[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };  // 2 per direction
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(directions.length())) return;
  vec2 uv = equirect_uv(directions[i].xyz);
  results[2u * i] = vec4(uv, equirect_pixel_solid_angle(int(i % 64u), 128, 64), 0.0f);
  results[2u * i + 1u] = vec4(equirect_direction(uv), 0.0f);
}
)";

TEST(EquirectGlsl, ComputeShaderMatchesCpp) {
  lucent::test::ensure_gl_context();
  const std::string source = "#version 450 core\n" + lucent::test::embedded_without_includes("shared/bridge.h") +
                             lucent::test::embedded_without_includes("bssrdf/constants.h") +
                             lucent::test::embedded_without_includes("lights/equirect.h") + kMain;
  const GLuint program = lucent::test::compile_compute_source(source);

  std::vector<glm::vec3> directions = lucent::sphere_directions(1000);
  directions.insert(directions.end(), {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, 1)});
  std::vector<glm::vec4> input;
  for (const glm::vec3& d : directions) input.emplace_back(d, 0.0f);
  std::vector<glm::vec4> output(2 * input.size());
  GLuint buffers[2];
  glCreateBuffers(2, buffers);
  glNamedBufferStorage(buffers[0], static_cast<GLsizeiptr>(input.size() * sizeof(glm::vec4)), input.data(), 0);
  glNamedBufferStorage(buffers[1], static_cast<GLsizeiptr>(output.size() * sizeof(glm::vec4)), nullptr, 0);
  glUseProgram(program);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  glDispatchCompute(static_cast<GLuint>((input.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffers[1], 0, static_cast<GLsizeiptr>(output.size() * sizeof(glm::vec4)), output.data());
  glDeleteBuffers(2, buffers);
  glDeleteProgram(program);

  // Tolerance: GPU atan/acos/sin/cos are approximations (llvmpipe: uv within 5e-5, directions within 1.6e-4);
  // a mirrored or shifted convention would be off by far more.
  using namespace lucent::shader;
  for (std::size_t i = 0; i < directions.size(); ++i) {
    const glm::vec2 uv = equirect_uv(directions[i]);
    const float solid_angle = equirect_pixel_solid_angle(static_cast<int>(i % 64), 128, 64);
    const glm::vec4 gpu_uv = output[2 * i], gpu_direction = output[2 * i + 1];
    ASSERT_TRUE(std::isfinite(gpu_uv.x) && std::isfinite(gpu_uv.y)) << "direction " << i;
    EXPECT_LT(glm::distance(glm::vec2(gpu_uv), uv), 5.0e-4f) << "direction " << i;
    EXPECT_NEAR(gpu_uv.z / solid_angle, 1.0f, 1.0e-4f) << "row " << i % 64;
    EXPECT_LT(glm::distance(glm::vec3(gpu_direction), directions[i]), 1.0e-3f) << "direction " << i;
  }
}

}  // namespace
