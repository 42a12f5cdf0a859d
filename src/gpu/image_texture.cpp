// image_texture.cpp: see image_texture.h.
#include "gpu/image_texture.h"

#include "gpu/gl_debug.h"

namespace lucent::gpu {

GLuint make_image_texture(int width, int height, GLenum format, std::string_view label) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, format, width, height);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  label_object(GL_TEXTURE, texture, label);
  return texture;
}

}  // namespace lucent::gpu
