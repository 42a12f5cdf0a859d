// layer_views.h: the views one layered G-buffer pass renders into, uploaded once and bound before each such pass
// at LUCENT_BINDING_LAYER_VIEWS, and the program that renders them: the pass draws its objects once per view
// (SceneGpu::draw_all(count())), and shaders/gbuffer/gbuffer.vert with LAYERED_VIEWS sends instance i to layer i
// through view i (gl_Layer from the vertex shader, GL_ARB_shader_viewport_layer_array). Instancing replaced a
// geometry shader with 32 invocations that cost ~7 ms per pass for a 70k-triangle mesh on an H100
// (docs/design.md, "Layered G-buffers").
#pragma once
#include <span>
#include <string_view>

#include <epoxy/gl.h>

#include "gpu/gl_debug.h"
#include "gpu/shader_program.h"
#include "lucent/error.h"
#include "shared/shader_io.h"

namespace lucent::gpu {

class LayerViews {
 public:
  LayerViews(std::span<const shader::ViewGPU> views, std::string_view label) : count_(views.size()) {
    if (views.size() > LUCENT_MAX_LAYERS) throw Error("a layered G-buffer pass has more than 64 views");
    glCreateBuffers(1, &buffer_);
    glNamedBufferStorage(buffer_, static_cast<GLsizeiptr>(std::max<std::size_t>(1, views.size()) * sizeof(shader::ViewGPU)),
                         views.empty() ? nullptr : views.data(), 0);
    label_object(GL_BUFFER, buffer_, label);
  }
  ~LayerViews() { glDeleteBuffers(1, &buffer_); }
  LayerViews(const LayerViews&) = delete;
  LayerViews& operator=(const LayerViews&) = delete;

  // Binds the views; an empty set binds nothing (a pass with no views draws nothing).
  void bind() const {
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LAYER_VIEWS, buffer_, 0,
                      static_cast<GLsizeiptr>(count_ * sizeof(shader::ViewGPU)));
  }
  std::size_t count() const { return count_; }

 private:
  std::size_t count_;
  GLuint buffer_ = 0;
};

// The G-buffer program of layered passes (position, normal and depth per layer).
inline ShaderProgram layered_gbuffer_program() {
  return ShaderProgram::graphics("gbuffer/gbuffer.vert", "", "gbuffer/gbuffer.frag", "#define LAYERED_VIEWS 1\n");
}

}  // namespace lucent::gpu
