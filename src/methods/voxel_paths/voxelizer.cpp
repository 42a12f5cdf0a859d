// voxelizer.cpp: see voxelizer.h.
#include "methods/voxel_paths/voxelizer.h"

#include <algorithm>

#include "gpu/gl_debug.h"

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
    : triangles_program_(gpu::ShaderProgram::compute("voxel_paths/voxelize_triangles.comp", shader_defines())),
      scan_program_(gpu::ShaderProgram::compute("voxel_paths/voxelize_scan.comp", shader_defines())),
      triangles_(make_buffer("voxel-paths triangles")),
      flips_(make_buffer("voxel-paths flips")),
      labels_(make_buffer("voxel-paths labels")) {}

Voxelizer::~Voxelizer() {
  GLuint buffers[] = {triangles_, flips_, labels_};
  glDeleteBuffers(3, buffers);
}

void Voxelizer::voxelize(const TranslucentTriangles& triangles, const VoxelGrid& grid) {
  gpu::DebugGroup group("voxelize");
  // Upload; the voxel buffers are reallocated only when the resolution changes.
  glNamedBufferData(triangles_, static_cast<GLsizeiptr>(std::max<std::size_t>(1, triangles.corners.size()) * 16),
                    triangles.corners.empty() ? nullptr : triangles.corners.data(), GL_DYNAMIC_DRAW);
  if (grid.voxel_count() != voxel_count_) {
    voxel_count_ = grid.voxel_count();
    glNamedBufferData(flips_, static_cast<GLsizeiptr>(voxel_count_ * 4), nullptr, GL_DYNAMIC_DRAW);
    glNamedBufferData(labels_, static_cast<GLsizeiptr>(voxel_count_ * 4), nullptr, GL_DYNAMIC_DRAW);
  }
  bytes_ = voxel_count_ * 8 + triangles.corners.size() * 16;
  const GLuint zero = 0;
  glClearNamedBufferData(labels_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingTriangles, triangles_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingFlips, flips_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingLabels, labels_);
  const auto r = static_cast<GLuint>(grid.resolution);
  for (const TranslucentTriangles::Range& object : triangles.objects) {
    // Crossings of this object's surface, then parity up each column.
    glClearNamedBufferData(flips_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    GLuint p = triangles_program_.id();
    glUseProgram(p);
    glUniform1ui(glGetUniformLocation(p, "u_first_triangle"), object.first_triangle);
    glUniform1ui(glGetUniformLocation(p, "u_triangle_count"), object.triangle_count);
    glUniform3fv(glGetUniformLocation(p, "u_origin"), 1, &grid.origin.x);
    glUniform1f(glGetUniformLocation(p, "u_voxel_size"), grid.voxel_size);
    glUniform1i(glGetUniformLocation(p, "u_resolution"), grid.resolution);
    glDispatchCompute((object.triangle_count + 63) / 64, 1, 1);
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
