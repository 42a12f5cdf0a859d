// gl_capabilities.cpp: version and limit checks shared by the EGL and GLFW contexts.
#include "platform/gl_capabilities.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "lucent/error.h"

namespace lucent::platform {
namespace {

GLCapabilities g_capabilities;

int get_integer(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

void require_limit(const char* name, int value, int required) {
  if (value < required)
    throw Error(fmt::format("OpenGL limit {} is {}, lucent needs at least {}", name, value, required));
}

}  // namespace

GLCapabilities check_capabilities() {
  int gl_version = epoxy_gl_version();
  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (gl_version < 45)
    throw Error(fmt::format("OpenGL 4.5 core is required; the driver offers {} ({})", version ? version : "none",
                            renderer ? renderer : "unknown renderer"));
  GLCapabilities caps;
  caps.renderer = renderer ? renderer : "";
  caps.version = version ? version : "";
  caps.is_llvmpipe = caps.renderer.find("llvmpipe") != std::string::npos;
  caps.is_nvidia = caps.renderer.find("NVIDIA") != std::string::npos;
  caps.max_array_texture_layers = get_integer(GL_MAX_ARRAY_TEXTURE_LAYERS);
  caps.max_geometry_shader_invocations = get_integer(GL_MAX_GEOMETRY_SHADER_INVOCATIONS);
  require_limit("GL_MAX_ARRAY_TEXTURE_LAYERS", caps.max_array_texture_layers, 64);
  require_limit("GL_MAX_GEOMETRY_SHADER_INVOCATIONS", caps.max_geometry_shader_invocations, 32);
  require_limit("GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS", get_integer(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS), 256);
  require_limit("GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS", get_integer(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS), 16);
  gpu::install_debug_output();
  g_capabilities = caps;
  return caps;
}

const GLCapabilities& current_capabilities() { return g_capabilities; }

}  // namespace lucent::platform
