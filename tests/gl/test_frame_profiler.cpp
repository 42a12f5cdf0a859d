// test_frame_profiler.cpp: a pass's time is the work of that pass on every driver. llvmpipe stamps a timestamp
// query when it flushes its queue, not where the query was issued, so unflushed a pass could be charged the work of
// the passes before it (random-walk's sphere_walks pass once showed the first trace dispatch's 1,289 ms). A pass of
// known cost between two cheap ones: its time is that cost (measured alone by wall clock with a finish), and the
// cheap ones stay cheap.
#include <chrono>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "gpu/frame_profiler.h"
#include "image_compare.h"

namespace {

TEST(FrameProfiler, APassIsChargedItsOwnWork) {
  lucent::test::ensure_gl_context();
  const char* source = R"(#version 450
    layout(local_size_x = 64) in;
    layout(std430, binding = 7) buffer Values { float values[]; };
    layout(location = 0) uniform uint iterations;
    void main() {
      float x = float(gl_GlobalInvocationID.x) * 1e-3;
      // loop bound: checked; iterations stays under llvmpipe's 65,535 (the test sets it)
      for (uint i = 0u; i < iterations; ++i) x = sin(x) * 0.999 + 0.5;
      values[gl_GlobalInvocationID.x] = x;
    })";
  const GLuint program = glCreateShaderProgramv(GL_COMPUTE_SHADER, 1, &source);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  ASSERT_EQ(linked, GL_TRUE);
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, 4096 * sizeof(float), nullptr, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, buffer);
  auto dispatch = [&](unsigned iterations) {
    glUseProgram(program);
    glProgramUniform1ui(program, 0, iterations);
    glDispatchCompute(64, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  };
  constexpr unsigned kHeavy = 40000, kLight = 4;
  dispatch(kHeavy);  // compiled and warm
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  dispatch(kHeavy);
  glFinish();
  const double alone_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  lucent::gpu::FrameProfiler profiler;
  profiler.begin_frame(1);
  { auto pass = profiler.pass("before"); dispatch(kLight); }
  {
    // A read-back ends the pass, as the random-walk's counters end a round of dispatches: it flushes the queue, and
    // unflushed timestamps queued before the dispatch would be stamped only then.
    auto pass = profiler.pass("heavy");
    dispatch(kHeavy);
    float first = 0.0f;
    glGetNamedBufferSubData(buffer, 0, sizeof(first), &first);
  }
  { auto pass = profiler.pass("after"); dispatch(kLight); }
  profiler.end_frame();
  const std::vector<lucent::gpu::ProfiledFrame> frames = profiler.collect(true);
  ASSERT_EQ(frames.size(), 1u);
  double before = -1, heavy = -1, after = -1;
  for (const auto& [name, ms] : frames[0].passes)
    (name == "before" ? before : name == "heavy" ? heavy : after) = ms;
  std::printf("alone %.2f ms; profiled: before %.3f, heavy %.2f, after %.3f ms\n", alone_ms, before, heavy, after);
  EXPECT_GT(heavy, 0.5 * alone_ms);
  EXPECT_LT(heavy, 2.0 * alone_ms);
  EXPECT_LT(before, 0.2 * heavy);
  EXPECT_LT(after, 0.2 * heavy);
  glDeleteBuffers(1, &buffer);
  glDeleteProgram(program);
}

}  // namespace
