// scene_gpu.h: a scene's geometry, materials and objects on the GPU. All objects share one world-space vertex
// buffer; translucent objects come first so that passes that need only them draw a prefix of the indices.
#pragma once
#include <memory>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "lucent/scene.h"

namespace lucent::geometry {
class BlobIsosurface;
}
namespace lucent::gpu {
class FrameProfiler;
}

namespace lucent::render {

struct BoundingSphere {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

class SceneGpu {
 public:
  // `model_tables`: whether the tabulated model's tables are made for the translucent materials (photon transport,
  // seconds per material); methods that estimate volpath instead of evaluating a model never read them.
  explicit SceneGpu(const Scene& scene, bool model_tables = true);
  ~SceneGpu();
  SceneGpu(const SceneGpu&) = delete;
  SceneGpu& operator=(const SceneGpu&) = delete;

  void bind_buffers() const;        // materials, objects and the tabulated model's tables (storage buffers)
  // Draw every object (or the translucent ones) `instances` times: layered passes draw one instance per view
  // (shaders/gbuffer/gbuffer.vert sets gl_Layer = gl_InstanceID).
  void draw_all(int instances = 1) const;
  void draw_translucent(int instances = 1) const;

  // Animated scenes: deforming objects' vertices are recomputed and uploaded, blob surfaces re-extracted on the
  // GPU, for time t. Bounds are conservative over the whole animation, so views built from them stay valid.
  bool animated() const { return !deforming_.empty() || !blobs_.empty(); }
  void update(double seconds, gpu::FrameProfiler* profiler);
  // New materials and opaque albedos for the same objects (same translucent set): re-uploads the two buffers.
  void update_materials(const Scene& scene);

  BoundingSphere translucent_bounds() const { return translucent_bounds_; }  // all bounds if none translucent
  // Axis-aligned box of the translucent objects, conservative over the animation like translucent_bounds().
  glm::vec3 translucent_lower() const { return translucent_lower_; }
  glm::vec3 translucent_upper() const { return translucent_upper_; }
  // The shared geometry, for passes that read triangles in compute shaders (voxel-paths' voxelizer): vertices
  // (shader::VertexGPU, updated every frame for deforming objects), indices, and each translucent mesh's range
  // of indices (blob surfaces are not in these buffers).
  struct MeshRange {
    std::uint32_t object;       // index into Scene::objects
    std::uint32_t first_index;  // into index_buffer()
    std::uint32_t index_count;
  };
  GLuint vertex_buffer() const { return vertex_buffer_; }
  GLuint index_buffer() const { return index_buffer_; }
  const std::vector<MeshRange>& translucent_meshes() const { return translucent_meshes_; }
  BoundingSphere scene_bounds() const { return scene_bounds_; }
  bool has_translucent() const { return translucent_index_count_ > 0 || translucent_blob_count_ > 0; }
  std::size_t gpu_memory_bytes() const;

 private:
  struct Deforming {
    std::size_t object;
    std::uint32_t first_vertex;
    TriangleMesh mesh;  // object space, undeformed
    glm::mat4 world_from_object;
    Deformation deformation;
  };
  std::vector<Deforming> deforming_;
  std::vector<std::unique_ptr<geometry::BlobIsosurface>> blobs_;  // translucent ones first
  std::size_t translucent_blob_count_ = 0;
  std::size_t vertex_bytes_ = 0;
  std::size_t material_count_ = 0;
  // The tabulated model's table array (materials/tabulated_bssrdf.h) as uploaded, and its generation then.
  void upload_bssrdf_tables();
  GLuint bssrdf_table_buffer_ = 0;
  GLuint material_map_buffer_ = 0;  // textured materials' texels (media/material_map.h)
  std::size_t material_map_bytes_ = 0;
  // Throws lucent::Error naming `source` when the texels exceed the driver's largest storage block.
  void upload_material_maps(const std::vector<glm::vec4>& texels, const std::string& source);
  std::uint64_t bssrdf_table_generation_ = 0;
  bool model_tables_ = true;  // the tabulated model's tables made for the translucent materials

  GLuint vao_ = 0, vertex_buffer_ = 0, index_buffer_ = 0, material_buffer_ = 0, object_buffer_ = 0;
  GLsizei translucent_index_count_ = 0, index_count_ = 0;
  BoundingSphere translucent_bounds_, scene_bounds_;
  glm::vec3 translucent_lower_{0.0f}, translucent_upper_{0.0f};
  std::vector<MeshRange> translucent_meshes_;
};

}  // namespace lucent::render
