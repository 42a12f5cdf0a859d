// gl_debug.cpp: KHR_debug plumbing.
#include "gpu/gl_debug.h"

#include <cstdio>
#include <cstdlib>

namespace lucent::gpu {
namespace {

void GLAPIENTRY on_debug_message(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei, const GLchar* message,
                                 const void*) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  std::fprintf(stderr, "lucent: GL debug [%s, type 0x%x, id %u]: %s\n",
               severity == GL_DEBUG_SEVERITY_HIGH ? "high" : "medium/low", type, id, message);
}

bool debug_requested() {
#if defined(LUCENT_GL_DEBUG)
  return true;
#else
  const char* env = std::getenv("LUCENT_GL_DEBUG");
  return env && env[0] == '1';
#endif
}

}  // namespace

void install_debug_output() {
  if (!debug_requested()) return;
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(on_debug_message, nullptr);
}

void label_object(GLenum identifier, GLuint name, std::string_view label) {
  glObjectLabel(identifier, name, static_cast<GLsizei>(label.size()), label.data());
}

DebugGroup::DebugGroup(std::string_view name) {
  glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, static_cast<GLsizei>(name.size()), name.data());
}

DebugGroup::~DebugGroup() { glPopDebugGroup(); }

}  // namespace lucent::gpu
