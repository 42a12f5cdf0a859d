// screen_targets.h: a method's own per-pixel surface pass: `count` RGBA32F colour targets (nearest filtering) and
// a depth target at the output's size, in one framebuffer, recreated when the output size changes.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "lucent/error.h"

namespace lucent::gpu {

class ScreenTargets {
 public:
  ScreenTargets(int count, std::string label) : colour_(static_cast<std::size_t>(count), 0), label_(std::move(label)) {}
  ~ScreenTargets() { release(); }
  ScreenTargets(const ScreenTargets&) = delete;
  ScreenTargets& operator=(const ScreenTargets&) = delete;

  // (Re)creates the targets at width x height; nothing when the size is unchanged. Throws lucent::Error when the
  // framebuffer is incomplete.
  void resize(int width, int height) {
    if (width == width_ && height == height_) return;
    release();
    glCreateFramebuffers(1, &framebuffer_);
    std::vector<GLenum> draw_buffers;
    for (std::size_t i = 0; i < colour_.size(); ++i) {
      glCreateTextures(GL_TEXTURE_2D, 1, &colour_[i]);
      glTextureStorage2D(colour_[i], 1, GL_RGBA32F, width, height);
      glTextureParameteri(colour_[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(colour_[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      const auto attachment = static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + i);
      glNamedFramebufferTexture(framebuffer_, attachment, colour_[i], 0);
      draw_buffers.push_back(attachment);
    }
    glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
    glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, width, height);
    glNamedFramebufferTexture(framebuffer_, GL_DEPTH_ATTACHMENT, depth_, 0);
    glNamedFramebufferDrawBuffers(framebuffer_, static_cast<GLsizei>(draw_buffers.size()), draw_buffers.data());
    label_object(GL_FRAMEBUFFER, framebuffer_, label_);
    if (glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw Error(fmt::format("{}: the {}x{} surface framebuffer is incomplete", label_, width, height));
    width_ = width, height_ = height;
  }

  // Binds the framebuffer and the viewport, clears the colours to 0 and the depth to 1, depth test on (less).
  void begin_pass() const {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glViewport(0, 0, width_, height_);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, one = 1.0f;
    for (std::size_t i = 0; i < colour_.size(); ++i)
      glClearNamedFramebufferfv(framebuffer_, GL_COLOR, static_cast<GLint>(i), zero);
    glClearNamedFramebufferfv(framebuffer_, GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
  }

  // Binds colour target i to texture unit first_unit + i, for every target.
  void bind_textures(GLuint first_unit) const {
    for (std::size_t i = 0; i < colour_.size(); ++i) glBindTextureUnit(first_unit + static_cast<GLuint>(i), colour_[i]);
  }

  std::size_t gpu_memory_bytes() const {
    return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * (colour_.size() * 16 + 4);
  }

 private:
  void release() {
    glDeleteTextures(static_cast<GLsizei>(colour_.size()), colour_.data());
    glDeleteTextures(1, &depth_);
    glDeleteFramebuffers(1, &framebuffer_);
    for (GLuint& t : colour_) t = 0;
    depth_ = framebuffer_ = 0;
    width_ = height_ = 0;
  }

  std::vector<GLuint> colour_;
  GLuint depth_ = 0, framebuffer_ = 0;
  int width_ = 0, height_ = 0;
  std::string label_;
};

}  // namespace lucent::gpu
