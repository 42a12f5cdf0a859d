// frame_counters.h: the per-frame atomic counters of shader_io.h's CountersGPU in a storage buffer bound at
// LUCENT_BINDING_COUNTERS: zeroed at the start of a method's frame, read back for statistics.
#pragma once
#include <epoxy/gl.h>

#include "gpu/gl_debug.h"
#include "shared/shader_io.h"

namespace lucent::gpu {

class FrameCounters {
 public:
  FrameCounters() {
    glCreateBuffers(1, &buffer_);
    glNamedBufferStorage(buffer_, sizeof(shader::CountersGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    label_object(GL_BUFFER, buffer_, "frame counters");
  }
  ~FrameCounters() { glDeleteBuffers(1, &buffer_); }
  FrameCounters(const FrameCounters&) = delete;
  FrameCounters& operator=(const FrameCounters&) = delete;

  void reset_and_bind() const {
    const shader::CountersGPU zero{};
    glNamedBufferSubData(buffer_, 0, sizeof(zero), &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_COUNTERS, buffer_);
  }
  shader::CountersGPU read() const {  // waits for the GPU
    shader::CountersGPU counters{};
    glGetNamedBufferSubData(buffer_, 0, sizeof(counters), &counters);
    return counters;
  }

 private:
  GLuint buffer_ = 0;
};

}  // namespace lucent::gpu
