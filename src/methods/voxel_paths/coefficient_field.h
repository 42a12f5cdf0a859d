// coefficient_field.h: the per-voxel edge-cost coefficients of voxel-paths (rgb, one vec4 per voxel, 0 outside):
// each inside voxel's material (by label) modified by the heterogeneous field of heterogeneous_field.h at the
// voxel centre. Filled on the GPU every frame after voxelization (shaders/voxel_paths/fill_coefficients.comp);
// coefficient_field() is the CPU evaluation of the same header for the tests and the CPU Dijkstra.
#pragma once
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/shader_program.h"
#include "methods/voxel_paths/voxel_grid.h"

namespace lucent::methods::voxel_paths {

struct FieldSettings {
  int field = shader::kFieldNone;  // kFieldNone, kFieldMarble or kFieldLayered
  float scale = 0.25f;             // feature size [scene units]: vein period, layer thickness unit
  float contrast = 4.0f;           // m ranges over [1, 1 + contrast]
};

// "none" | "marble" | "layered" -> kField*; throws lucent::Error for anything else.
int field_from_name(std::string_view name);

// CPU evaluation: per voxel, rgb coefficient (0 outside). materials: per label (TranslucentTriangles::materials).
std::vector<glm::vec4> coefficient_field(const VoxelGrid& grid, std::span<const std::uint32_t> labels,
                                         std::span<const shader::FieldMaterialGPU> materials,
                                         const FieldSettings& settings);

class CoefficientField {
 public:
  CoefficientField();
  ~CoefficientField();
  CoefficientField(const CoefficientField&) = delete;
  CoefficientField& operator=(const CoefficientField&) = delete;

  // Uploads the per-label materials and fills the per-voxel coefficients from the labels.
  void fill(const VoxelGrid& grid, GLuint labels_buffer, std::span<const shader::FieldMaterialGPU> materials,
            const FieldSettings& settings);

  GLuint buffer() const { return coefficients_; }  // vec4 per voxel, rgb [1/scene unit]
  std::vector<glm::vec4> read() const;
  std::size_t gpu_memory_bytes() const { return voxel_count_ * 16; }

 private:
  gpu::ShaderProgram program_;
  GLuint coefficients_ = 0, materials_ = 0;
  std::size_t voxel_count_ = 0;
};

}  // namespace lucent::methods::voxel_paths
