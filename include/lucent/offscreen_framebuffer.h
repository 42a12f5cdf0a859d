// offscreen_framebuffer.h: an RGBA8 framebuffer for rendering without a window (headless tools, tests,
// benchmarks). Applications with their own framebuffer pass that to Renderer::render instead.
#pragma once

namespace lucent {

class OffscreenFramebuffer {
 public:
  OffscreenFramebuffer(int width, int height);  // needs a current GL context
  ~OffscreenFramebuffer();
  OffscreenFramebuffer(const OffscreenFramebuffer&) = delete;
  OffscreenFramebuffer& operator=(const OffscreenFramebuffer&) = delete;
  unsigned id() const { return framebuffer_; }

 private:
  unsigned framebuffer_ = 0, color_ = 0;
};

}  // namespace lucent
