// scene_gpu.h: a scene's geometry, materials and objects on the GPU. All objects share one world-space vertex
// buffer; translucent objects come first so that passes that need only them draw a prefix of the indices.
#pragma once
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "lucent/scene.h"

namespace lucent::render {

struct BoundingSphere {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

class SceneGpu {
 public:
  explicit SceneGpu(const Scene& scene);
  ~SceneGpu();
  SceneGpu(const SceneGpu&) = delete;
  SceneGpu& operator=(const SceneGpu&) = delete;

  void bind_buffers() const;        // materials and objects storage buffers
  void draw_all() const;
  void draw_translucent() const;

  BoundingSphere translucent_bounds() const { return translucent_bounds_; }  // all bounds if none translucent
  BoundingSphere scene_bounds() const { return scene_bounds_; }
  bool has_translucent() const { return translucent_index_count_ > 0; }

 private:
  GLuint vao_ = 0, vertex_buffer_ = 0, index_buffer_ = 0, material_buffer_ = 0, object_buffer_ = 0;
  GLsizei translucent_index_count_ = 0, index_count_ = 0;
  BoundingSphere translucent_bounds_, scene_bounds_;
};

}  // namespace lucent::render
