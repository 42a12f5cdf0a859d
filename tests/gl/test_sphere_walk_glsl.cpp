// test_sphere_walk_glsl.cpp: the canonical walk of the sphere jumps (shared/sphere_walk.h) is embedded for the
// shaders, compiles as GLSL 4.50 and gives the same records in a compute shader as in C++. Its random numbers come
// from a counter, not from the positions, so the two walks take the same turns and differ only by the rounding of
// the transcendental functions, unless a flight ends within that rounding of the sphere (rare).
#include <cmath>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "gpu/shader_sources.h"
#include "image_compare.h"
#include "shared/sphere_walk.h"

namespace {

const char* kSwMain = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) writeonly buffer Records { SphereWalkGPU records[]; };
uniform float u_radius;
uniform float u_g;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(records.length())) return;
  records[i] = sphere_walk(u_radius, u_g, seed_from(7u, i, 0u, 0u));
}
)";

TEST(SphereWalkGlsl, ComputeShaderMatchesCpp) {
  lucent::test::ensure_gl_context();
  const std::string source = "#version 450 core\n" + lucent::test::embedded_without_includes("shared/bridge.h") +
                             lucent::test::embedded_without_includes("shared/random.h") +
                             lucent::test::embedded_without_includes("shared/volume_walk.h") +
                             lucent::test::embedded_without_includes("shared/sphere_walk.h") + kSwMain;
  const GLuint program = lucent::test::compile_compute_source(source);
  ASSERT_NE(program, 0u);

  constexpr int kRecords = 1024;
  using lucent::shader::SphereWalkGPU;
  for (const float radius : {2.0f, 8.0f})
    for (const float g : {0.0f, 0.8f}) {
      GLuint buffer = 0;
      glCreateBuffers(1, &buffer);
      glNamedBufferStorage(buffer, kRecords * static_cast<GLsizeiptr>(sizeof(SphereWalkGPU)), nullptr, 0);
      glUseProgram(program);
      glProgramUniform1f(program, glGetUniformLocation(program, "u_radius"), radius);
      glProgramUniform1f(program, glGetUniformLocation(program, "u_g"), g);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
      glDispatchCompute(kRecords / 64, 1, 1);
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      std::vector<SphereWalkGPU> gpu(kRecords);
      glGetNamedBufferSubData(buffer, 0, kRecords * static_cast<GLsizeiptr>(sizeof(SphereWalkGPU)), gpu.data());
      glDeleteBuffers(1, &buffer);
      int other_turns = 0;
      for (int i = 0; i < kRecords; ++i) {
        const SphereWalkGPU cpu =
            lucent::shader::sphere_walk(radius, g, lucent::shader::seed_from(7u, static_cast<std::uint32_t>(i), 0u, 0u));
        const SphereWalkGPU& gl = gpu[static_cast<std::size_t>(i)];
        ASSERT_TRUE(std::isfinite(gl.exit.w)) << "record " << i;
        if (gl.exit_dir.w != cpu.exit_dir.w || gl.vertex_dir.w != cpu.vertex_dir.w) {
          ++other_turns;
          continue;
        }
        const float tolerance = 1e-3f * (1.0f + cpu.exit.w);
        EXPECT_LT(glm::distance(gl.exit, cpu.exit), tolerance) << "record " << i << " radius " << radius << " g " << g;
        EXPECT_LT(glm::distance(glm::vec3(gl.exit_dir), glm::vec3(cpu.exit_dir)), tolerance) << "record " << i;
        EXPECT_LT(glm::distance(gl.vertex, cpu.vertex), tolerance) << "record " << i;
        EXPECT_LT(glm::distance(glm::vec3(gl.vertex_dir), glm::vec3(cpu.vertex_dir)), tolerance) << "record " << i;
      }
      std::printf("radius %.0f g %.1f: %d of %d records took another turn\n", radius, g, other_turns, kRecords);
      EXPECT_LE(other_turns, kRecords / 100) << "radius " << radius << " g " << g;
    }
  glDeleteProgram(program);
}

}  // namespace
