// blob_isosurface.h: the implicit blob scene's surface (geometry/blob_field.h), extracted on the GPU every frame
// by marching tetrahedra (geometry/marching_tetrahedra.h) into an indexed triangle buffer drawn with
// glDrawElementsIndirect, with no CPU readback in the frame.
//
// Passes per extract(), all compute: sample the field at the grid points; classify (crossing edges, vertex
// and triangle counts per point, and a list of the points that emit anything); exclusive scan of the counts
// (deterministic offsets, so the output order is the CPU reference's, geometry/isosurface_cpu.h); finalize
// (totals, overflow flag, indirect draw and dispatch commands); emit over the active points only (vertices in
// shared::VertexGPU layout, 3 indices per triangle), dispatched indirectly.
#pragma once
#include <cstdint>
#include <vector>

#include <epoxy/gl.h>

#include "geometry/isosurface_grid.h"
#include "geometry/isosurface_io.h"
#include "gpu/shader_program.h"
#include "lucent/mesh.h"
#include "shared/shader_io.h"

namespace lucent::gpu {
class FrameProfiler;
}

namespace lucent::geometry {

struct IsosurfaceCounts {
  std::uint32_t vertices = 0;   // what the surface needs, even beyond the capacity
  std::uint32_t triangles = 0;
  bool over_capacity = false;   // then nothing is drawn
};

class BlobIsosurface {
 public:
  // Needs a current OpenGL 4.5 core context. Compiles the shaders and allocates every buffer for a surface of
  // up to `max_triangles` triangles (0: default_capacity(grid)); vertices carry `object_index` in position.w.
  // Throws lucent::Error for a grid outside 2 to 1024 cells per axis or with an empty box, a missing GL limit,
  // buffers larger than GL_MAX_SHADER_STORAGE_BLOCK_SIZE, or a shader error.
  BlobIsosurface(const IsosurfaceGrid& grid, int object_index, std::uint32_t max_triangles = 0);
  ~BlobIsosurface();
  BlobIsosurface(const BlobIsosurface&) = delete;
  BlobIsosurface& operator=(const BlobIsosurface&) = delete;

  // Extracts the surface at `time_seconds`; returns without waiting for the GPU. Ends with the barriers for
  // drawing (vertex, index, indirect) and reading back the buffers. Throws lucent::Error when an earlier
  // extraction whose counts have reached the CPU (checked without waiting, at most a few frames late)
  // needed more than the capacity. With `profiler`, each pass is timed under "isosurface <pass>".
  void extract(float time_seconds, gpu::FrameProfiler* profiler = nullptr);

  // Draws the last extraction `instances` times (layered passes draw one instance per view): binds its vertex
  // array and GL_DRAW_INDIRECT_BUFFER, sets the command's instance count, glDrawElementsIndirect.
  void draw(int instances = 1) const;

  // The buffers, for drawing with one's own state: vertex_buffer() holds shader::VertexGPU (gpu/vertex_layout.h:
  // attribute 0: vec4 position, 1: vec4 normal, 2: vec4 texture coordinates, always 0 here; stride 48),
  // index_buffer() GL_UNSIGNED_INT triangles, indirect_buffer() one DrawElementsIndirectCommand (count = 3 x
  // triangles, or 0 over capacity). vertex_array() binds the first two with that layout.
  GLuint vertex_buffer() const { return buffers_[kVertices]; }
  GLuint index_buffer() const { return buffers_[kIndices]; }
  GLuint indirect_buffer() const { return buffers_[kDraw]; }
  GLuint vertex_array() const { return vao_; }

  const IsosurfaceGrid& grid() const { return grid_; }
  std::uint32_t max_triangles() const { return max_triangles_; }
  std::size_t gpu_memory_bytes() const;

  // Default capacity: 16 (nx ny + ny nz + nz nx) triangles for nx x ny x nz cells (about 5 x what the blob
  // scene needs at its largest on blob_grid: 26,880 for 5,396 at resolution 32, 430,064 for 87,348 at 128).
  static std::uint32_t default_capacity(const IsosurfaceGrid& grid);

  // Readbacks of the last extraction, for tests and tools: they wait for the GPU.
  // read_counts throws lucent::Error when it needed more than the capacity.
  IsosurfaceCounts read_counts() const;
  std::vector<shader::VertexGPU> read_vertices() const;  // the emitted vertices
  std::vector<std::uint32_t> read_indices() const;       // 3 per emitted triangle
  TriangleMesh read_mesh() const;                        // positions and normals (xyz), indices
  std::vector<float> read_samples() const;               // stored sample per grid point (point_index)

 private:
  enum Buffer { kParams, kSamples, kMasks, kOffsets, kScanSums, kActive, kDispatch, kVertices, kIndices, kCounts,
                kDraw, kReadback, kBufferCount };
  struct ScanLevel {
    GLintptr offset;      // into the buffer holding this level's data (kOffsets for level 0, else kScanSums)
    std::uint32_t count;  // elements
  };
  void scan(gpu::FrameProfiler* profiler);
  void check_previous_counts();
  IsosurfaceCounts counts_from(const shader::IsosurfaceCountsGPU& gpu) const;

  IsosurfaceGrid grid_;
  int object_index_ = 0;
  std::uint32_t max_triangles_ = 0;
  std::uint32_t max_active_points_ = 0;  // grid points with a vertex or a triangle: at most 2 x max_triangles
  gpu::ShaderProgram sample_, classify_, scan_, scan_add_, finalize_, emit_;
  GLuint buffers_[kBufferCount] = {};
  GLuint vao_ = 0;
  mutable int command_instances_ = 1;  // instance count in the kDraw command (finalize writes 1)
  std::vector<ScanLevel> scan_levels_;
  std::size_t scan_sums_bytes_ = 0;
  GLsync readback_fence_ = nullptr;
  const shader::IsosurfaceCountsGPU* readback_ = nullptr;  // persistently mapped copy of kCounts
};

}  // namespace lucent::geometry
