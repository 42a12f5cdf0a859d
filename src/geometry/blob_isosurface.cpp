// blob_isosurface.cpp: GPU marching tetrahedra of the blob field; passes and buffers in blob_isosurface.h.
#include "geometry/blob_isosurface.h"

#include <algorithm>
#include <cstddef>

#include <fmt/format.h>

#include "geometry/isosurface_io.h"
#include "geometry/marching_tetrahedra.h"
#include "gpu/gl_debug.h"
#include "gpu/frame_profiler.h"
#include "gpu/vertex_layout.h"
#include "lucent/error.h"

namespace lucent::geometry {
namespace {

using shader::DrawElementsIndirectGPU;
using shader::IsosurfaceCountsGPU;
using shader::IsosurfaceDispatchGPU;
using shader::IsosurfaceParamsGPU;
using shader::VertexGPU;

constexpr GLuint kPointGroup = 4;  // local size per axis of the per-point passes

int get_integer(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

GLuint make_buffer(GLsizeiptr bytes, GLbitfield flags, const char* label, const void* data = nullptr) {
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, std::max<GLsizeiptr>(bytes, 16), data, flags);
  gpu::label_object(GL_BUFFER, buffer, label);
  return buffer;
}

GLsizeiptr buffer_size(GLuint buffer) {
  GLint64 size = 0;
  glGetNamedBufferParameteri64v(buffer, GL_BUFFER_SIZE, &size);
  return static_cast<GLsizeiptr>(size);
}

GLuint groups(std::uint64_t count, std::uint64_t per_group) {
  return static_cast<GLuint>((count + per_group - 1) / per_group);
}

}  // namespace

std::uint32_t BlobIsosurface::default_capacity(const IsosurfaceGrid& grid) {
  auto c = glm::u64vec3(grid.cells);
  std::uint64_t cross_sections = c.x * c.y + c.y * c.z + c.z * c.x;
  return static_cast<std::uint32_t>(std::clamp<std::uint64_t>(16 * cross_sections, 4096, 1u << 28));
}

BlobIsosurface::BlobIsosurface(const IsosurfaceGrid& grid, int object_index, std::uint32_t max_triangles)
    : grid_(grid), object_index_(object_index), max_triangles_(max_triangles ? max_triangles : default_capacity(grid)) {
  // Step 1: check the grid and the GL limits.
  if (glm::any(glm::lessThan(grid.cells, glm::ivec3(2))) || glm::any(glm::greaterThan(grid.cells, glm::ivec3(1024))))
    throw Error(fmt::format("blob isosurface: grid of {}x{}x{} cells; each axis needs 2 to 1024 cells", grid.cells.x,
                            grid.cells.y, grid.cells.z));
  if (glm::any(glm::lessThanEqual(grid.upper, grid.lower)))
    throw Error("blob isosurface: the grid box's upper corner must exceed its lower corner on every axis");
  if (get_integer(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS) <= LUCENT_ISO_MAX_BINDING)
    throw Error(fmt::format("blob isosurface: GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS is {}, it needs {}",
                            get_integer(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS), LUCENT_ISO_MAX_BINDING + 1));
  std::uint64_t point_count = grid.point_count();
  std::uint64_t largest = std::max<std::uint64_t>(std::uint64_t{max_triangles_} * sizeof(VertexGPU), point_count * 8);
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  if (largest > static_cast<std::uint64_t>(max_block))
    throw Error(fmt::format("blob isosurface: a buffer of {} bytes exceeds GL_MAX_SHADER_STORAGE_BLOCK_SIZE ({}); "
                            "use a smaller grid or capacity", largest, max_block));
  // Every active point owns a vertex or a triangle, so a surface within capacity has at most 2 x capacity.
  max_active_points_ =
      static_cast<std::uint32_t>(std::min<std::uint64_t>(point_count, 2 * std::uint64_t{max_triangles_}));

  // Step 2: programs.
  sample_ = gpu::ShaderProgram::compute("geometry/blob_sample.comp");
  classify_ = gpu::ShaderProgram::compute("geometry/isosurface_classify.comp");
  scan_ = gpu::ShaderProgram::compute("geometry/prefix_scan.comp");
  scan_add_ = gpu::ShaderProgram::compute("geometry/prefix_scan_add.comp");
  finalize_ = gpu::ShaderProgram::compute("geometry/isosurface_finalize.comp");
  emit_ = gpu::ShaderProgram::compute("geometry/isosurface_emit.comp");

  // Step 3: scan levels; the last level's single block writes the totals into kCounts.
  auto alignment = static_cast<std::size_t>(std::max(1, get_integer(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT)));
  scan_levels_.push_back({0, static_cast<std::uint32_t>(point_count)});
  while (scan_levels_.back().count > LUCENT_SCAN_BLOCK) {
    std::uint32_t blocks = groups(scan_levels_.back().count, LUCENT_SCAN_BLOCK);
    scan_sums_bytes_ = (scan_sums_bytes_ + alignment - 1) / alignment * alignment;
    scan_levels_.push_back({static_cast<GLintptr>(scan_sums_bytes_), blocks});
    scan_sums_bytes_ += std::size_t{blocks} * 8;
  }

  // Step 4: buffers and the vertex array.
  auto points = static_cast<GLsizeiptr>(point_count);
  auto capacity = static_cast<GLsizeiptr>(max_triangles_);
  buffers_[kParams] = make_buffer(sizeof(IsosurfaceParamsGPU), GL_DYNAMIC_STORAGE_BIT, "isosurface params");
  buffers_[kSamples] = make_buffer(points * 4, 0, "isosurface samples");
  buffers_[kMasks] = make_buffer(points * 4, 0, "isosurface edge masks");
  buffers_[kOffsets] = make_buffer(points * 8, 0, "isosurface offsets");
  buffers_[kScanSums] = make_buffer(static_cast<GLsizeiptr>(scan_sums_bytes_), 0, "isosurface scan sums");
  buffers_[kActive] = make_buffer(static_cast<GLsizeiptr>(max_active_points_) * 4, 0, "isosurface active points");
  buffers_[kDispatch] = make_buffer(sizeof(IsosurfaceDispatchGPU), 0, "isosurface emit dispatch");
  buffers_[kVertices] = make_buffer(capacity * static_cast<GLsizeiptr>(sizeof(VertexGPU)), 0, "isosurface vertices");
  buffers_[kIndices] = make_buffer(capacity * 12, 0, "isosurface indices");
  buffers_[kCounts] = make_buffer(sizeof(IsosurfaceCountsGPU), 0, "isosurface counts");
  DrawElementsIndirectGPU empty{0, 1, 0, 0, 0};  // draws nothing before the first extraction
  buffers_[kDraw] = make_buffer(sizeof(empty), GL_DYNAMIC_STORAGE_BIT, "isosurface draw command", &empty);
  GLbitfield mapped = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  buffers_[kReadback] = make_buffer(sizeof(IsosurfaceCountsGPU), mapped, "isosurface counts readback");
  readback_ = static_cast<const IsosurfaceCountsGPU*>(
      glMapNamedBufferRange(buffers_[kReadback], 0, sizeof(IsosurfaceCountsGPU), mapped));
  glCreateVertexArrays(1, &vao_);
  gpu::set_vertex_gpu_layout(vao_, buffers_[kVertices]);
  glVertexArrayElementBuffer(vao_, buffers_[kIndices]);
  gpu::label_object(GL_VERTEX_ARRAY, vao_, "isosurface");
}

BlobIsosurface::~BlobIsosurface() {
  if (readback_fence_) glDeleteSync(readback_fence_);
  glDeleteBuffers(kBufferCount, buffers_);
  glDeleteVertexArrays(1, &vao_);
}

std::size_t BlobIsosurface::gpu_memory_bytes() const {
  std::size_t bytes = 0;
  for (GLuint buffer : buffers_) bytes += static_cast<std::size_t>(buffer_size(buffer));
  return bytes;
}

void BlobIsosurface::extract(float time_seconds, gpu::FrameProfiler* profiler) {
  check_previous_counts();
  gpu::DebugGroup group("blob isosurface");
  IsosurfaceParamsGPU params{};
  params.lower = glm::vec4(grid_.lower, time_seconds);
  params.spacing = glm::vec4(grid_.spacing(), static_cast<float>(object_index_));
  params.cells = glm::ivec4(grid_.cells, 0);
  params.limits = glm::uvec4(max_triangles_, max_active_points_, 0, 0);
  params.field = shader::blob_state(time_seconds);
  glNamedBufferSubData(buffers_[kParams], 0, sizeof(params), &params);
  glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_ISO_PARAMS, buffers_[kParams]);
  glm::uvec3 point_groups = (glm::uvec3(grid_.points()) + kPointGroup - 1u) / kPointGroup;
  auto dispatch_points = [&](const gpu::ShaderProgram& program) {
    glUseProgram(program.id());
    glDispatchCompute(point_groups.x, point_groups.y, point_groups.z);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  };

  // Step 1: samples; crossing edges, counts and the active list per point.
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_ISO_SAMPLES, buffers_[kSamples]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_ISO_MASKS, buffers_[kMasks]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_ISO_OFFSETS, buffers_[kOffsets]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_ISO_ACTIVE, buffers_[kActive]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_ISO_DISPATCH, buffers_[kDispatch]);
  glClearNamedBufferSubData(buffers_[kDispatch], GL_R32UI, offsetof(IsosurfaceDispatchGPU, active_points), 4,
                            GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  {
    gpu::FrameProfiler::Pass t(profiler, "isosurface sample");
    dispatch_points(sample_);
  }
  {
    gpu::FrameProfiler::Pass t(profiler, "isosurface classify");
    dispatch_points(classify_);
  }

  // Step 2: counts -> first vertex and triangle of each point; totals -> overflow flag and draw command.
  scan(profiler);
  {
    gpu::FrameProfiler::Pass t(profiler, "isosurface finalize");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_ISO_COUNTS, buffers_[kCounts]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_ISO_DRAW, buffers_[kDraw]);
    glUseProgram(finalize_.id());
    glDispatchCompute(1, 1, 1);
    command_instances_ = 1;
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  }

  // Step 3: vertices and triangles of the active points.
  {
    gpu::FrameProfiler::Pass t(profiler, "isosurface emit");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_ISO_VERTICES, buffers_[kVertices]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_ISO_INDICES, buffers_[kIndices]);
    glUseProgram(emit_.id());
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, buffers_[kDispatch]);
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  }
  glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
                  GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);

  // Step 4: a copy of the counts for the CPU, read when it has arrived (check_previous_counts).
  if (!readback_fence_) {
    glCopyNamedBufferSubData(buffers_[kCounts], buffers_[kReadback], 0, 0, sizeof(IsosurfaceCountsGPU));
    readback_fence_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  }
}

void BlobIsosurface::scan(gpu::FrameProfiler* profiler) {
  gpu::FrameProfiler::Pass t(profiler, "isosurface scan");
  auto bind_level = [&](GLuint binding, std::size_t level) {
    const ScanLevel& l = scan_levels_[level];
    GLuint buffer = level == 0 ? buffers_[kOffsets] : buffers_[kScanSums];
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, binding, buffer, l.offset, static_cast<GLsizeiptr>(l.count) * 8);
  };
  // Up: scan each level's blocks, their totals forming the next level (the last one's: the grand totals).
  glUseProgram(scan_.id());
  for (std::size_t level = 0; level < scan_levels_.size(); ++level) {
    bind_level(LUCENT_BINDING_SCAN_DATA, level);
    if (level + 1 < scan_levels_.size()) bind_level(LUCENT_BINDING_SCAN_SUMS, level + 1);
    else glBindBufferRange(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_SCAN_SUMS, buffers_[kCounts], 0, 8);
    glProgramUniform1ui(scan_.id(), 0, scan_levels_[level].count);
    glDispatchCompute(groups(scan_levels_[level].count, LUCENT_SCAN_BLOCK), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  // Down: add each block's offset to its elements.
  glUseProgram(scan_add_.id());
  for (std::size_t level = scan_levels_.size() - 1; level-- > 0;) {
    bind_level(LUCENT_BINDING_SCAN_DATA, level);
    bind_level(LUCENT_BINDING_SCAN_SUMS, level + 1);
    glProgramUniform1ui(scan_add_.id(), 0, scan_levels_[level].count);
    glDispatchCompute(groups(scan_levels_[level].count, LUCENT_SCAN_BLOCK), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

IsosurfaceCounts BlobIsosurface::counts_from(const IsosurfaceCountsGPU& gpu) const {
  IsosurfaceCounts counts{gpu.totals.x, gpu.totals.y, gpu.totals.z != 0};
  if (counts.over_capacity)
    throw Error(fmt::format("blob isosurface: the surface needs {} triangles and {} vertices, over the capacity of "
                            "{} ({}x{}x{} grid); pass a larger max_triangles",
                            counts.triangles, counts.vertices, max_triangles_, grid_.cells.x, grid_.cells.y,
                            grid_.cells.z));
  return counts;
}

void BlobIsosurface::check_previous_counts() {
  if (!readback_fence_) return;
  GLenum status = glClientWaitSync(readback_fence_, 0, 0);
  if (status != GL_ALREADY_SIGNALED && status != GL_CONDITION_SATISFIED) return;
  glDeleteSync(readback_fence_);
  readback_fence_ = nullptr;
  counts_from(*readback_);
}

void BlobIsosurface::draw(int instances) const {
  if (instances != command_instances_) {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // after finalize's writes to the same command
    const auto count = static_cast<GLuint>(instances);
    glNamedBufferSubData(buffers_[kDraw], offsetof(DrawElementsIndirectGPU, instance_count), sizeof(count), &count);
    command_instances_ = instances;
  }
  glBindVertexArray(vao_);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, buffers_[kDraw]);
  glDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

IsosurfaceCounts BlobIsosurface::read_counts() const {
  IsosurfaceCountsGPU gpu{};
  glGetNamedBufferSubData(buffers_[kCounts], 0, sizeof(gpu), &gpu);
  return counts_from(gpu);
}

std::vector<VertexGPU> BlobIsosurface::read_vertices() const {
  std::vector<VertexGPU> vertices(read_counts().vertices);
  glGetNamedBufferSubData(buffers_[kVertices], 0, static_cast<GLsizeiptr>(vertices.size() * sizeof(VertexGPU)),
                          vertices.data());
  return vertices;
}

std::vector<std::uint32_t> BlobIsosurface::read_indices() const {
  std::vector<std::uint32_t> indices(std::size_t{read_counts().triangles} * 3);
  glGetNamedBufferSubData(buffers_[kIndices], 0, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
                          indices.data());
  return indices;
}

TriangleMesh BlobIsosurface::read_mesh() const {
  TriangleMesh mesh;
  for (const VertexGPU& v : read_vertices()) {
    mesh.positions.emplace_back(v.position);
    mesh.normals.emplace_back(v.normal);
  }
  mesh.indices = read_indices();
  return mesh;
}

std::vector<float> BlobIsosurface::read_samples() const {
  std::vector<float> samples(grid_.point_count());
  glGetNamedBufferSubData(buffers_[kSamples], 0, static_cast<GLsizeiptr>(samples.size() * sizeof(float)),
                          samples.data());
  return samples;
}

}  // namespace lucent::geometry
