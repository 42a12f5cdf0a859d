// voxelizer.h: solid voxelization of the translucent objects on the GPU by parity counting along z
// (src/methods/voxel_paths/shaders/voxelize_triangles.comp, voxelize_scan.comp), from triangles already on the GPU. Objects must be closed meshes; where they
// overlap, the later object's label wins. Cost: one invocation per triangle over the columns its projection
// covers, then one per column; no rasterization, so no conservative-raster or MSAA requirement.
#pragma once
#include <cstdint>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/shader_program.h"
#include "methods/voxel_paths/voxel_grid.h"

namespace lucent::methods::voxel_paths {

// Triangles to voxelize, read in place on the GPU: shader::VertexGPU vertices, uint indices, one range of
// indices per object with the label its inside voxels get. The renderer's SceneGpu buffers (deforming objects
// included: their vertices are updated there every frame) or an upload of TranslucentTriangles.
struct TriangleSource {
  GLuint vertices = 0;
  GLuint indices = 0;
  struct Range {
    std::uint32_t first_index, index_count, label;
  };
  std::vector<Range> objects;
};

class Voxelizer {
 public:
  Voxelizer();
  ~Voxelizer();
  Voxelizer(const Voxelizer&) = delete;
  Voxelizer& operator=(const Voxelizer&) = delete;

  // Labels every voxel of `grid` (0 outside, the object's label inside).
  void voxelize(const TriangleSource& source, const VoxelGrid& grid);
  // Uploads CPU triangles (labels: object index + 1) and voxelizes them.
  void voxelize(const TranslucentTriangles& triangles, const VoxelGrid& grid);

  GLuint labels_buffer() const { return labels_; }    // uint per voxel
  std::vector<std::uint32_t> read_labels() const;
  std::size_t gpu_memory_bytes() const { return bytes_; }

 private:
  gpu::ShaderProgram triangles_program_, scan_program_;
  GLuint vertices_ = 0, indices_ = 0, flips_ = 0, labels_ = 0;
  std::size_t voxel_count_ = 0, bytes_ = 0;
};

}  // namespace lucent::methods::voxel_paths
