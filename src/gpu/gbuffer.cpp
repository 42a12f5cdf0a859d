// gbuffer.cpp: G-buffer textures and framebuffer.
#include "gpu/gbuffer.h"

#include <algorithm>
#include <cstdint>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "lucent/error.h"

namespace lucent::gpu {
namespace {

GLuint make_texture(int size_x, int size_y, int layers, GLenum format, const std::string& label) {
  GLuint texture = 0;
  glCreateTextures(layers == 0 ? GL_TEXTURE_2D : GL_TEXTURE_2D_ARRAY, 1, &texture);
  if (layers == 0)
    glTextureStorage2D(texture, 1, format, size_x, size_y);
  else
    glTextureStorage3D(texture, 1, format, size_x, size_y, layers);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  label_object(GL_TEXTURE, texture, label);
  return texture;
}

}  // namespace

GBuffer::GBuffer(int size_x, int size_y, int layers, const std::string& name, bool with_uv)
    : size_x_(size_x), size_y_(size_y), layers_(layers) {
  position_ = make_texture(size_x, size_y, layers, GL_RGBA32F, name + " position");
  normal_ = make_texture(size_x, size_y, layers, GL_RGBA16F, name + " normal");
  depth_ = make_texture(size_x, size_y, layers, GL_DEPTH_COMPONENT32F, name + " depth");
  glCreateFramebuffers(1, &framebuffer_);
  glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, position_, 0);
  glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT1, normal_, 0);
  glNamedFramebufferTexture(framebuffer_, GL_DEPTH_ATTACHMENT, depth_, 0);
  if (with_uv) {
    uv_ = make_texture(size_x, size_y, layers, GL_RG32F, name + " texture coordinates");
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT2, uv_, 0);
  }
  const GLenum draw_buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  glNamedFramebufferDrawBuffers(framebuffer_, with_uv ? 3 : 2, draw_buffers);
  label_object(GL_FRAMEBUFFER, framebuffer_, name);
  const std::uint64_t bytes = static_cast<std::uint64_t>(size_x) * static_cast<std::uint64_t>(size_y) *
                              static_cast<std::uint64_t>(std::max(1, layers)) * (16 + 8 + 4 + (with_uv ? 8 : 0));
  if (glGetError() == GL_OUT_OF_MEMORY)
    throw Error(fmt::format("{}: out of GPU memory for {}x{}x{} texels ({:.1f} MiB)", name, size_x, size_y,
                            std::max(1, layers), static_cast<double>(bytes) / (1024.0 * 1024.0)));
  GLenum status = glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw Error(fmt::format("{}: framebuffer of {}x{}x{} texels ({:.1f} MiB) incomplete (status 0x{:x}): the driver "
                            "refused its size or format",
                            name, size_x, size_y, std::max(1, layers), static_cast<double>(bytes) / (1024.0 * 1024.0),
                            status));
}

GBuffer::~GBuffer() {
  glDeleteFramebuffers(1, &framebuffer_);
  GLuint textures[] = {position_, normal_, depth_, uv_};
  glDeleteTextures(uv_ != 0 ? 4 : 3, textures);
}

void GBuffer::begin_pass(bool farthest) const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, size_x_, size_y_);
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const float clear_depth = farthest ? 0.0f : 1.0f;
  glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 1, zero);
  if (uv_ != 0) glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 2, zero);
  glClearNamedFramebufferfv(framebuffer_, GL_DEPTH, 0, &clear_depth);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(farthest ? GL_GREATER : GL_LESS);
  glDisable(GL_CULL_FACE);
}

void GBuffer::bind_uv(GLuint unit) const { glBindTextureUnit(unit, uv_); }

void GBuffer::bind_textures(GLuint position_unit, GLuint normal_unit, GLuint depth_unit) const {
  glBindTextureUnit(position_unit, position_);
  glBindTextureUnit(normal_unit, normal_);
  glBindTextureUnit(depth_unit, depth_);
}

}  // namespace lucent::gpu
