// voxelizer.h: solid voxelization of the translucent objects on the GPU by parity counting along z
// (shaders/voxel_paths/voxelize_triangles.comp, voxelize_scan.comp). Objects must be closed meshes; where they
// overlap, the later object's label wins. Cost: one invocation per triangle over the columns its projection
// covers, then one per column; no rasterization, so no conservative-raster or MSAA requirement.
#pragma once
#include <cstdint>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/shader_program.h"
#include "methods/voxel_paths/voxel_grid.h"

namespace lucent::methods::voxel_paths {

class Voxelizer {
 public:
  Voxelizer();
  ~Voxelizer();
  Voxelizer(const Voxelizer&) = delete;
  Voxelizer& operator=(const Voxelizer&) = delete;

  // Uploads the triangles and labels every voxel of `grid` (0 outside, object index + 1).
  void voxelize(const TranslucentTriangles& triangles, const VoxelGrid& grid);

  GLuint labels_buffer() const { return labels_; }    // uint per voxel
  std::vector<std::uint32_t> read_labels() const;
  std::size_t gpu_memory_bytes() const { return bytes_; }

 private:
  gpu::ShaderProgram triangles_program_, scan_program_;
  GLuint triangles_ = 0, flips_ = 0, labels_ = 0;
  std::size_t voxel_count_ = 0, bytes_ = 0;
};

}  // namespace lucent::methods::voxel_paths
