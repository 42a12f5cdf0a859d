// test_multipole_glsl.cpp: the multipole model (bssrdf/multipole.h) compiles as GLSL 4.50 and gives in a compute
// shader the profiles (one source and spread along the beam) and totals it gives in C++, over albedos, eta,
// thicknesses and distances.
#include <cmath>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "bssrdf/multipole.h"
#include "image_compare.h"

namespace {

const char* kMain = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Cases { vec4 cases[]; };       // albedo, eta, thickness, r
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };  // 2 per case
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(cases.length())) return;
  vec4 c = cases[i];
  BandMedium m = make_band_medium(1.0f - c.x, c.x, 0.0f);
  results[2u * i] = vec4(multipole_Rd(m, c.y, c.z, c.w), multipole_Td(m, c.y, c.z, c.w),
                         multipole_beam_profiles(m, c.y, c.z, c.w, 16));
  results[2u * i + 1u] = vec4(multipole_totals(c.x, c.y, c.z), multipole_beam_totals(c.x, c.y, c.z));
}
)";

TEST(MultipoleGlsl, ComputeShaderMatchesCpp) {
  lucent::test::ensure_gl_context();
  std::string source = "#version 450 core\n";
  for (const char* header : {"shared/bridge.h", "bssrdf/constants.h", "bssrdf/fresnel.h", "bssrdf/medium.h",
                             "bssrdf/standard_dipole.h", "bssrdf/multipole.h"})
    source += lucent::test::embedded_without_includes(header);
  const GLuint program = lucent::test::compile_compute_source(source + kMain);
  ASSERT_NE(program, 0u);

  std::vector<glm::vec4> cases;
  for (float albedo : {0.8f, 0.95f, 0.999f})
    for (float eta : {1.0f, 1.4f})
      for (float thickness : {1.5f, 4.0f, 32.0f})
        for (float r : {0.01f, 0.3f, 1.0f, 3.0f, 10.0f}) cases.emplace_back(albedo, eta, thickness, r);
  std::vector<glm::vec4> output(2 * cases.size());
  GLuint buffers[2];
  glCreateBuffers(2, buffers);
  glNamedBufferStorage(buffers[0], static_cast<GLsizeiptr>(cases.size() * sizeof(glm::vec4)), cases.data(), 0);
  glNamedBufferStorage(buffers[1], static_cast<GLsizeiptr>(output.size() * sizeof(glm::vec4)), nullptr, 0);
  glUseProgram(program);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  glDispatchCompute(static_cast<GLuint>((cases.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffers[1], 0, static_cast<GLsizeiptr>(output.size() * sizeof(glm::vec4)), output.data());
  glDeleteBuffers(2, buffers);
  glDeleteProgram(program);

  // Tolerance: the GPU's exp and log against the C++ library's, over sums of up to 2112 terms: 1e-4 relative, or
  // 1e-6 of the largest value where terms cancel to near zero, or 1e-9 absolute (a profile 20 mean free paths
  // through the slab: llvmpipe's exp at -20 is 3e-4 off relative, 3e-11 absolute).
  using namespace lucent::shader;
  auto near = [](float gpu, float cpu, float scale) {
    return std::fabs(gpu - cpu) <= 1e-4f * std::fabs(cpu) + 1e-6f * scale + 1e-9f;
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const glm::vec4 c = cases[i];
    const BandMedium m = make_band_medium(1.0f - c.x, c.x, 0.0f);
    const float rd = multipole_Rd(m, c.y, c.z, c.w), td = multipole_Td(m, c.y, c.z, c.w);
    const vec2 beam_profiles = multipole_beam_profiles(m, c.y, c.z, c.w, 16);
    const vec2 totals = multipole_totals(c.x, c.y, c.z), beam = multipole_beam_totals(c.x, c.y, c.z);
    const glm::vec4 a = output[2 * i], b = output[2 * i + 1];
    const float profile_scale = std::max(std::fabs(rd), std::fabs(td));
    EXPECT_TRUE(near(a.x, rd, profile_scale)) << "R(r) case " << i << ": " << a.x << " vs " << rd;
    EXPECT_TRUE(near(a.y, td, profile_scale)) << "T(r) case " << i << ": " << a.y << " vs " << td;
    const float beam_scale = std::max(std::fabs(beam_profiles.x), std::fabs(beam_profiles.y));
    EXPECT_TRUE(near(a.z, beam_profiles.x, beam_scale) && near(a.w, beam_profiles.y, beam_scale))
        << "beam profiles case " << i << ": " << a.z << ", " << a.w << " vs " << beam_profiles.x << ", " << beam_profiles.y;
    EXPECT_TRUE(near(b.x, totals.x, 1.0f) && near(b.y, totals.y, 1.0f)) << "totals case " << i;
    EXPECT_TRUE(near(b.z, beam.x, 1.0f) && near(b.w, beam.y, 1.0f)) << "beam totals case " << i;
  }
}

}  // namespace
