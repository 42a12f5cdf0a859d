// offscreen_framebuffer.cpp: see offscreen_framebuffer.h.
#include "lucent/offscreen_framebuffer.h"

#include <epoxy/gl.h>

#include "gpu/gl_debug.h"

namespace lucent {

OffscreenFramebuffer::OffscreenFramebuffer(int width, int height) {
  glCreateRenderbuffers(1, &color_);
  glNamedRenderbufferStorage(color_, GL_RGBA8, width, height);
  glCreateFramebuffers(1, &framebuffer_);
  glNamedFramebufferRenderbuffer(framebuffer_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  gpu::label_object(GL_FRAMEBUFFER, framebuffer_, "offscreen framebuffer");
}

OffscreenFramebuffer::~OffscreenFramebuffer() {
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteRenderbuffers(1, &color_);
}

}  // namespace lucent
