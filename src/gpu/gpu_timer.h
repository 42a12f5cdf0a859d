// gpu_timer.h: per-pass GPU times from GL timestamp queries (glQueryCounter), keyed by pass name.
// Timestamps rather than GL_TIME_ELAPSED: llvmpipe returned a garbage first GL_TIME_ELAPSED result (353 s for a
// 1 s run) and timestamps also allow passes to be adjacent without a gap.
#pragma once
#include <string>
#include <vector>

#include <epoxy/gl.h>

namespace lucent::gpu {

class GpuTimer {
 public:
  GpuTimer() = default;
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;
  ~GpuTimer();

  void begin_frame();
  void begin(const std::string& pass);  // passes may not nest
  void end();
  // Waits for the frame's queries; returns (pass, milliseconds) in submission order, equal names summed.
  std::vector<std::pair<std::string, double>> resolve();

 private:
  struct Query {
    std::string pass;
    GLuint begin, end;  // GL_TIMESTAMP queries around the pass
  };
  GLuint next_query();
  std::vector<GLuint> pool_;
  std::vector<Query> active_;
  std::size_t used_ = 0;
};

}  // namespace lucent::gpu
