// coefficient_field.h: the per-voxel edge-cost coefficients of voxel-paths (rgb, one vec4 per voxel, 0 outside):
// each inside voxel's material (by label) modified by its heterogeneous field (media/heterogeneous_field.h) at the
// voxel centre. Filled on the GPU every frame after voxelization (src/methods/voxel_paths/shaders/fill_coefficients.comp);
// coefficient_field() is the CPU evaluation of the same header for the tests and the CPU Dijkstra.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/shader_program.h"
#include "methods/voxel_paths/voxel_grid.h"

namespace lucent::methods::voxel_paths {

// CPU evaluation: per voxel, rgb coefficient (0 outside) from each label's material and field (`triangles`).
std::vector<glm::vec4> coefficient_field(const VoxelGrid& grid, std::span<const std::uint32_t> labels,
                                         const TranslucentTriangles& triangles);
// The field multiplier m of a label's material at p (CPU; the GPU evaluates the same in fill_coefficients.comp).
float field_multiplier_at(const shader::FieldMaterialGPU& material, const MediumVolume* volume, glm::vec3 p);

class CoefficientField {
 public:
  CoefficientField();
  ~CoefficientField();
  CoefficientField(const CoefficientField&) = delete;
  CoefficientField& operator=(const CoefficientField&) = delete;

  // Uploads the per-label materials (and the volume field once) and fills the per-voxel coefficients.
  void fill(const VoxelGrid& grid, GLuint labels_buffer, const TranslucentTriangles& triangles);

  GLuint buffer() const { return coefficients_; }  // vec4 per voxel, rgb [1/scene unit]
  std::vector<glm::vec4> read() const;
  std::size_t gpu_memory_bytes() const { return voxel_count_ * 16 + volume_bytes_; }

 private:
  gpu::ShaderProgram program_;
  GLuint coefficients_ = 0, materials_ = 0, volume_texture_ = 0;
  const MediumVolume* uploaded_volume_ = nullptr;
  std::size_t voxel_count_ = 0, volume_bytes_ = 0;
};

}  // namespace lucent::methods::voxel_paths
