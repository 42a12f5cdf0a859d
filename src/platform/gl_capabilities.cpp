// gl_capabilities.cpp: version and limit checks shared by the EGL and GLFW contexts.
#include "platform/gl_capabilities.h"

#include <unistd.h>

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
  constexpr GLenum kTotalAvailableMemoryNvx = 0x9048;  // GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX, in KiB
  if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info"))
    caps.device_memory_bytes = static_cast<std::uint64_t>(get_integer(kTotalAvailableMemoryNvx)) * 1024u;
  else if (caps.is_llvmpipe)
    caps.device_memory_bytes = static_cast<std::uint64_t>(sysconf(_SC_PHYS_PAGES)) * static_cast<std::uint64_t>(sysconf(_SC_PAGE_SIZE));
  require_limit("GL_MAX_ARRAY_TEXTURE_LAYERS", caps.max_array_texture_layers, 64);
  // Layered G-buffers set gl_Layer in the vertex shader (gpu/layer_views.h).
  if (!epoxy_has_gl_extension("GL_ARB_shader_viewport_layer_array"))
    throw Error(fmt::format("OpenGL extension GL_ARB_shader_viewport_layer_array is required; the driver ({}) lacks it",
                            caps.renderer));
  require_limit("GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS", get_integer(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS), 256);
  require_limit("GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS", get_integer(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS), 16);
  gpu::install_debug_output();
  g_capabilities = caps;
  return caps;
}

const GLCapabilities& current_capabilities() { return g_capabilities; }

void require_device_memory(std::uint64_t bytes, const std::string& what) {
  const std::uint64_t available = g_capabilities.device_memory_bytes;
  if (available == 0 || bytes <= available) return;
  constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
  throw Error(fmt::format("{}: {:.1f} GiB of GPU memory needed; the device ({}) has {:.1f} GiB", what,
                          static_cast<double>(bytes) / kGiB, g_capabilities.renderer,
                          static_cast<double>(available) / kGiB));
}

void check_loop_iterations(std::string_view what, std::uint64_t iterations, std::string_view advice) {
  if (!g_capabilities.is_llvmpipe || iterations <= kLlvmpipeLoopBudget) return;
  throw Error(fmt::format("{} = {} shader loop iterations per invocation; llvmpipe ends an invocation's loops past {} "
                          "({})",
                          what, iterations, kLlvmpipeLoopBudget, advice));
}

}  // namespace lucent::platform
