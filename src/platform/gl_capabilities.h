// gl_capabilities.h: the one place for driver capabilities, required limits and workarounds.
#pragma once
#include <string>

namespace lucent::platform {

struct GLCapabilities {
  std::string renderer;  // GL_RENDERER
  std::string version;   // GL_VERSION
  bool is_llvmpipe = false;  // Mesa software rasterizer: slow; tests keep resolutions small
  bool is_nvidia = false;
  int max_array_texture_layers = 0;
  int max_geometry_shader_invocations = 0;
};

// Queries the current context and throws lucent::Error naming the missing version or limit.
GLCapabilities check_capabilities();
const GLCapabilities& current_capabilities();

}  // namespace lucent::platform
