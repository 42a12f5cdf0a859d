// environment_texture.h: a scene's environment map on the GPU (RGB32F equirectangular texture with box-filtered
// mips, repeating in u, clamped in v), bound at LUCENT_TEX_ENVIRONMENT for the specular lookup and background.
#pragma once
#include <epoxy/gl.h>

#include "lucent/environment.h"

namespace lucent::render {

class EnvironmentTexture {
 public:
  explicit EnvironmentTexture(const EnvironmentMap& map, int max_width = 1024);
  ~EnvironmentTexture();
  EnvironmentTexture(const EnvironmentTexture&) = delete;
  EnvironmentTexture& operator=(const EnvironmentTexture&) = delete;

  void bind() const;
  std::size_t gpu_memory_bytes() const { return bytes_; }

 private:
  GLuint texture_ = 0;
  std::size_t bytes_ = 0;
};

}  // namespace lucent::render
