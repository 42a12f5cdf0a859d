// frame_profiler.h: per-pass GPU times and the frame's counters, read back a few frames late so that a frame
// never waits for the GPU. A ring of kFramesInFlight slots, each with its GL_TIMESTAMP queries, a CountersGPU
// buffer and a fence: a frame's slot is collected when the ring comes round to it again (by then its fence has
// normally signalled), or on demand by collect(wait = true).
// Timestamps rather than GL_TIME_ELAPSED: llvmpipe returned a garbage first GL_TIME_ELAPSED result (353 s for a
// 1 s run), and timestamps let passes be adjacent without a gap.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/gl_debug.h"
#include "shared/shader_io.h"

namespace lucent::gpu {

// One frame as the GPU finished it.
struct ProfiledFrame {
  std::uint64_t frame = 0;                             // the number begin_frame() was given
  std::vector<std::pair<std::string, double>> passes;  // (name, ms) in submission order, equal names summed
  shader::CountersGPU counters{};
};

class FrameProfiler {
 public:
  static constexpr int kFramesInFlight = 4;

  // One timed pass: a debug group and two timestamps under one name. Passes may not nest.
  class Pass {
   public:
    Pass(FrameProfiler* profiler, std::string_view name);
    ~Pass();
    Pass(const Pass&) = delete;
    Pass& operator=(const Pass&) = delete;

   private:
    FrameProfiler* profiler_;
    DebugGroup group_;
  };

  FrameProfiler();
  ~FrameProfiler();
  FrameProfiler(const FrameProfiler&) = delete;
  FrameProfiler& operator=(const FrameProfiler&) = delete;

  // Starts frame `number`: takes the next slot (collecting it first if it still holds an older frame), zeroes
  // its counters and binds them at LUCENT_BINDING_COUNTERS.
  void begin_frame(std::uint64_t number);
  Pass pass(std::string_view name) { return Pass(this, name); }
  void end_frame();  // after the frame's last pass: fences the slot

  // Frames the GPU has finished since the last call, oldest first. wait = false never blocks (a slot whose
  // fence has not signalled stays for later); wait = true waits for every frame in flight.
  std::vector<ProfiledFrame> collect(bool wait);

 private:
  struct Query {
    std::string pass;
    GLuint begin = 0, end = 0;
  };
  struct Slot {
    std::uint64_t frame = 0;
    bool pending = false;  // ended and not yet collected
    GLsync fence = nullptr;
    GLuint counters = 0;
    std::vector<GLuint> pool;
    std::size_t used = 0;
    std::vector<Query> queries;
  };
  GLuint next_query(Slot& slot);
  void begin_pass(std::string_view name);
  void end_pass();
  bool ready(Slot& slot, bool wait);
  ProfiledFrame read(Slot& slot);

  std::array<Slot, kFramesInFlight> slots_;
  bool flush_timestamps_ = false;  // platform::timestamps_need_flush: each query is flushed to be stamped in place
  int current_ = -1;
  bool in_frame_ = false;
  std::vector<ProfiledFrame> finished_;  // collected when their slot was reused, not yet handed out
};

}  // namespace lucent::gpu
