// environment_texture.cpp: see environment_texture.h.
#include "render/environment_texture.h"

#include <cmath>

#include "gpu/gl_debug.h"
#include "shared/shader_io.h"

namespace lucent::render {

EnvironmentTexture::EnvironmentTexture(const EnvironmentMap& map, int max_width) {
  lucent::EnvironmentTexture texels = make_environment_texture(map, max_width);
  int levels = 1 + static_cast<int>(std::floor(std::log2(static_cast<float>(texels.width))));
  glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
  glTextureStorage2D(texture_, levels, GL_RGB32F, texels.width, texels.height);
  glTextureSubImage2D(texture_, 0, 0, 0, texels.width, texels.height, GL_RGB, GL_FLOAT, texels.rgb.data());
  glGenerateTextureMipmap(texture_);
  glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gpu::label_object(GL_TEXTURE, texture_, "environment map");
  bytes_ = static_cast<std::size_t>(texels.width) * static_cast<std::size_t>(texels.height) * 12 * 4 / 3;
}

EnvironmentTexture::~EnvironmentTexture() { glDeleteTextures(1, &texture_); }

void EnvironmentTexture::bind() const { glBindTextureUnit(LUCENT_TEX_ENVIRONMENT, texture_); }

}  // namespace lucent::render
