// gbuffer.h: a geometry buffer (world position + object id, world normal, depth; texture coordinates where a
// scene has textured materials) as 2D textures or as 2D array textures for layered rendering, with its framebuffer.
#pragma once
#include <string>

#include <epoxy/gl.h>

namespace lucent::gpu {

class GBuffer {
 public:
  // layers == 0: plain 2D textures; layers >= 1: 2D array textures with that many layers. with_uv: a third
  // attachment (RG32F) holds the surface's texture coordinates (shaders/gbuffer/gbuffer.frag always writes them;
  // without the attachment they are dropped, so scenes without textured materials pay nothing).
  GBuffer(int size_x, int size_y, int layers, const std::string& name, bool with_uv = false);
  ~GBuffer();
  GBuffer(const GBuffer&) = delete;
  GBuffer& operator=(const GBuffer&) = delete;

  // Binds the framebuffer, sets the viewport and clears (position w = 0 marks empty texels). Nearest surface
  // wins (depth cleared to 1, GL_LESS), or with `farthest` the farthest one (cleared to 0, GL_GREATER).
  void begin_pass(bool farthest = false) const;
  void bind_textures(GLuint position_unit, GLuint normal_unit, GLuint depth_unit) const;
  void bind_uv(GLuint unit) const;  // with_uv only
  bool has_uv() const { return uv_ != 0; }

  int size_x() const { return size_x_; }
  int size_y() const { return size_y_; }
  int layers() const { return layers_; }
  GLuint position() const { return position_; }
  GLuint normal() const { return normal_; }

 private:
  int size_x_, size_y_, layers_;
  GLuint framebuffer_ = 0, position_ = 0, normal_ = 0, depth_ = 0, uv_ = 0;
};

}  // namespace lucent::gpu
