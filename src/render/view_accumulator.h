// view_accumulator.h: the running per-pixel sum of a view-dependent method (per-pixel, texture-space-is, hybrid):
// an RGBA32F image of the output's size (rgb: sum of the estimates, a: their count) that starts again when the
// caller says so, when the camera moves or when the output is resized.
#pragma once
#include <cstring>
#include <string>

#include <epoxy/gl.h>

#include "gpu/gl_debug.h"
#include "shared/shader_io.h"

namespace lucent::render {

class ViewAccumulator {
 public:
  explicit ViewAccumulator(std::string label) : label_(std::move(label)) {}
  ~ViewAccumulator() { glDeleteTextures(1, &texture_); }
  ViewAccumulator(const ViewAccumulator&) = delete;
  ViewAccumulator& operator=(const ViewAccumulator&) = delete;

  // Starts the frame: true when it restarts the sum (`restart`, a camera move or a new output size), after which
  // the image has the frame's size.
  bool begin_frame(const shader::FrameGPU& frame, bool restart) {
    const bool camera_moved = std::memcmp(&frame.clip_from_world, &last_camera_, sizeof(last_camera_)) != 0;
    last_camera_ = frame.clip_from_world;
    const int width = frame.output_size.x, height = frame.output_size.y;
    const bool resized = width != width_ || height != height_;
    restart = restart || camera_moved || resized;
    frames_ = restart ? 1 : frames_ + 1;
    if (resized) allocate(width, height);
    return restart;
  }

  void bind(int image_unit) const {
    glBindImageTexture(static_cast<GLuint>(image_unit), texture_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  }
  int frames() const { return frames_; }
  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t gpu_memory_bytes() const {
    return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 16;
  }

 private:
  void allocate(int width, int height) {
    glDeleteTextures(1, &texture_);
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_RGBA32F, width, height);
    gpu::label_object(GL_TEXTURE, texture_, label_);
    width_ = width, height_ = height;
  }

  std::string label_;
  GLuint texture_ = 0;
  int width_ = 0, height_ = 0, frames_ = 0;
  glm::mat4 last_camera_{0.0f};
};

}  // namespace lucent::render
