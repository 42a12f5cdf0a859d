// gl_debug.h: KHR_debug output (debug builds), object labels and debug groups named after passes.
#pragma once
#include <string_view>

#include <epoxy/gl.h>

namespace lucent::gpu {

// Installs the KHR_debug message callback (builds with LUCENT_GL_DEBUG, or LUCENT_GL_DEBUG=1 in the
// environment). Messages of high severity are printed to stderr.
void install_debug_output();
void label_object(GLenum identifier, GLuint name, std::string_view label);

// RAII debug group; the same name is used by the GPU timer and the profiler output.
class DebugGroup {
 public:
  explicit DebugGroup(std::string_view name);
  ~DebugGroup();
  DebugGroup(const DebugGroup&) = delete;
  DebugGroup& operator=(const DebugGroup&) = delete;
};

}  // namespace lucent::gpu
