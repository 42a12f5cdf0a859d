// coefficient_field.cpp: see coefficient_field.h.
#include "methods/voxel_paths/coefficient_field.h"

#include <algorithm>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "lucent/error.h"

namespace lucent::methods::voxel_paths {

float field_multiplier_at(const shader::FieldMaterialGPU& material, const MediumVolume* volume, glm::vec3 p) {
  const auto type = static_cast<int>(material.field.x);
  const glm::vec3 lower(material.lower), upper(material.upper);
  if (type == shader::kFieldVolume)
    return volume ? volume->multiplier((p - lower) / glm::max(upper - lower, glm::vec3(1e-12f))) : 1.0f;
  return shader::field_multiplier(type, p, lower, upper, material.field.y, material.field.z);
}

std::vector<glm::vec4> coefficient_field(const VoxelGrid& grid, std::span<const std::uint32_t> labels,
                                         const TranslucentTriangles& triangles) {
  std::vector<glm::vec4> out(grid.voxel_count(), glm::vec4(0.0f));
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (labels[i] == 0) continue;
    const shader::FieldMaterialGPU& material = triangles.materials[labels[i]];
    float m = field_multiplier_at(material, triangles.volume.get(), grid.center(grid.voxel(i)));
    out[i] = glm::vec4(shader::field_coefficient(material, m), 0.0f);
  }
  return out;
}

CoefficientField::CoefficientField()
    : program_(gpu::ShaderProgram::compute("methods/voxel_paths/shaders/fill_coefficients.comp", shader_defines())) {
  GLuint buffers[2];
  glCreateBuffers(2, buffers);
  coefficients_ = buffers[0], materials_ = buffers[1];
  glNamedBufferData(coefficients_, 16, nullptr, GL_DYNAMIC_DRAW);
  glNamedBufferData(materials_, sizeof(shader::FieldMaterialGPU), nullptr, GL_DYNAMIC_DRAW);
  gpu::label_object(GL_BUFFER, coefficients_, "voxel-paths coefficients");
  gpu::label_object(GL_BUFFER, materials_, "voxel-paths field materials");
}

CoefficientField::~CoefficientField() {
  GLuint buffers[] = {coefficients_, materials_};
  glDeleteBuffers(2, buffers);
  if (volume_texture_) glDeleteTextures(1, &volume_texture_);
}

void CoefficientField::fill(const VoxelGrid& grid, GLuint labels_buffer, const TranslucentTriangles& triangles) {
  gpu::DebugGroup group("voxel_field");
  const std::vector<shader::FieldMaterialGPU>& materials = triangles.materials;
  static_assert(sizeof(shader::FieldMaterialGPU) == 96);
  glNamedBufferData(materials_, static_cast<GLsizeiptr>(std::max<std::size_t>(1, materials.size()) * 96),
                    materials.empty() ? nullptr : materials.data(), GL_DYNAMIC_DRAW);
  if (grid.voxel_count() != voxel_count_) {
    voxel_count_ = grid.voxel_count();
    glNamedBufferData(coefficients_, static_cast<GLsizeiptr>(voxel_count_ * 16), nullptr, GL_DYNAMIC_DRAW);
  }
  if (triangles.volume.get() != uploaded_volume_ || !volume_texture_) {
    // The volume field as an R32F 3D texture, read with texelFetch (trilinear in the shader, as on the CPU).
    const MediumVolume* volume = triangles.volume.get();
    const glm::ivec3 size = volume ? volume->size : glm::ivec3(1);
    const float one = 1.0f;
    if (volume_texture_) glDeleteTextures(1, &volume_texture_);
    glCreateTextures(GL_TEXTURE_3D, 1, &volume_texture_);
    glTextureStorage3D(volume_texture_, 1, GL_R32F, size.x, size.y, size.z);
    glTextureSubImage3D(volume_texture_, 0, 0, 0, 0, size.x, size.y, size.z, GL_RED, GL_FLOAT,
                        volume ? volume->values.data() : &one);
    gpu::label_object(GL_TEXTURE, volume_texture_, "voxel-paths volume field");
    uploaded_volume_ = volume;
    volume_bytes_ = volume ? volume->values.size() * 4 : 0;
  }
  glBindTextureUnit(kTextureVolume, volume_texture_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingLabels, labels_buffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingSigmaT, coefficients_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingFieldMaterials, materials_);
  const GLuint p = program_.id();
  glUseProgram(p);
  glUniform3fv(glGetUniformLocation(p, "u_origin"), 1, &grid.origin.x);
  glUniform1f(glGetUniformLocation(p, "u_voxel_size"), grid.voxel_size);
  glUniform1i(glGetUniformLocation(p, "u_resolution"), grid.resolution);
  const auto groups = (static_cast<GLuint>(grid.resolution) + 3) / 4;
  glDispatchCompute(groups, groups, groups);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

std::vector<glm::vec4> CoefficientField::read() const {
  std::vector<glm::vec4> out(voxel_count_);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(coefficients_, 0, static_cast<GLsizeiptr>(out.size() * 16), out.data());
  return out;
}

}  // namespace lucent::methods::voxel_paths
