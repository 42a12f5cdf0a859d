// layer_views.h: the views one layered G-buffer pass renders into (shaders/gbuffer/layered_views.geom reads them
// from a storage buffer bound at LUCENT_BINDING_LAYER_VIEWS): uploaded once, bound before each such pass.
#pragma once
#include <span>
#include <string_view>

#include <epoxy/gl.h>

#include "gpu/gl_debug.h"
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

}  // namespace lucent::gpu
