// voxelizer.cpp: see voxelizer.h.
#include "methods/voxel_paths/voxelizer.h"

#include <algorithm>

#include "gpu/gl_debug.h"
#include "shared/shader_io.h"

namespace lucent::methods::voxel_paths {
namespace {

GLuint make_buffer(const char* label) {
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferData(buffer, 16, nullptr, GL_DYNAMIC_DRAW);
  gpu::label_object(GL_BUFFER, buffer, label);
  return buffer;
}

}  // namespace

Voxelizer::Voxelizer()
    : triangles_program_(gpu::ShaderProgram::compute("methods/voxel_paths/shaders/voxelize_triangles.comp", shader_defines())),
      scan_program_(gpu::ShaderProgram::compute("methods/voxel_paths/shaders/voxelize_scan.comp", shader_defines())),
      vertices_(make_buffer("voxel-paths uploaded vertices")),
      indices_(make_buffer("voxel-paths uploaded indices")),
      flips_(make_buffer("voxel-paths flips")),
      labels_(make_buffer("voxel-paths labels")) {}

Voxelizer::~Voxelizer() {
  GLuint buffers[] = {vertices_, indices_, flips_, labels_};
  glDeleteBuffers(4, buffers);
}

void Voxelizer::voxelize(const TranslucentTriangles& triangles, const VoxelGrid& grid) {
  std::vector<shader::VertexGPU> vertices(triangles.corners.size());
  std::vector<std::uint32_t> indices(triangles.corners.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    vertices[i] = {triangles.corners[i] - glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), glm::vec4(0.0f), glm::vec4(0.0f)};  // w: object index
    indices[i] = static_cast<std::uint32_t>(i);
  }
  glNamedBufferData(vertices_, static_cast<GLsizeiptr>(std::max<std::size_t>(1, vertices.size()) * sizeof(shader::VertexGPU)),
                    vertices.empty() ? nullptr : vertices.data(), GL_DYNAMIC_DRAW);
  glNamedBufferData(indices_, static_cast<GLsizeiptr>(std::max<std::size_t>(1, indices.size()) * 4),
                    indices.empty() ? nullptr : indices.data(), GL_DYNAMIC_DRAW);
  TriangleSource source{vertices_, indices_, {}};
  for (const TranslucentTriangles::Range& object : triangles.objects)
    source.objects.push_back({3 * object.first_triangle, 3 * object.triangle_count, object.label});
  voxelize(source, grid);
}

void Voxelizer::voxelize(const TriangleSource& source, const VoxelGrid& grid) {
  gpu::DebugGroup group("voxelize");
  // The voxel buffers are reallocated only when the resolution changes.
  if (grid.voxel_count() != voxel_count_) {
    voxel_count_ = grid.voxel_count();
    glNamedBufferData(flips_, static_cast<GLsizeiptr>(voxel_count_ * 4), nullptr, GL_DYNAMIC_DRAW);
    glNamedBufferData(labels_, static_cast<GLsizeiptr>(voxel_count_ * 4), nullptr, GL_DYNAMIC_DRAW);
  }
  bytes_ = voxel_count_ * 8;
  const GLuint zero = 0;
  glClearNamedBufferData(labels_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingTriangles, source.vertices);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingIndices, source.indices);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingFlips, flips_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingLabels, labels_);
  const auto r = static_cast<GLuint>(grid.resolution);
  for (const TriangleSource::Range& object : source.objects) {
    // Crossings of this object's surface, then parity up each column.
    glClearNamedBufferData(flips_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    GLuint p = triangles_program_.id();
    glUseProgram(p);
    const GLuint triangle_count = object.index_count / 3;
    glUniform1ui(glGetUniformLocation(p, "u_first_index"), object.first_index);
    glUniform1ui(glGetUniformLocation(p, "u_triangle_count"), triangle_count);
    glUniform3fv(glGetUniformLocation(p, "u_origin"), 1, &grid.origin.x);
    glUniform1f(glGetUniformLocation(p, "u_voxel_size"), grid.voxel_size);
    glUniform1i(glGetUniformLocation(p, "u_resolution"), grid.resolution);
    // Four row slices per triangle: at resolution 256 one invocation loops over at most 64 x 256 columns, under
    // llvmpipe's loop budget, which one whole grid of 256^2 columns passes.
    glDispatchCompute((triangle_count + 63) / 64, 4, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    p = scan_program_.id();
    glUseProgram(p);
    glUniform1i(glGetUniformLocation(p, "u_resolution"), grid.resolution);
    glUniform1ui(glGetUniformLocation(p, "u_label"), object.label);
    glDispatchCompute((r + 7) / 8, (r + 7) / 8, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }
}

std::vector<std::uint32_t> Voxelizer::read_labels() const {
  std::vector<std::uint32_t> labels(voxel_count_);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(labels_, 0, static_cast<GLsizeiptr>(labels.size() * 4), labels.data());
  return labels;
}

}  // namespace lucent::methods::voxel_paths
