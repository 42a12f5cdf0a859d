// coefficient_field.cpp: see coefficient_field.h.
#include "methods/voxel_paths/coefficient_field.h"

#include <algorithm>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "lucent/error.h"

namespace lucent::methods::voxel_paths {

int field_from_name(std::string_view name) {
  if (name == "none") return shader::kFieldNone;
  if (name == "marble") return shader::kFieldMarble;
  if (name == "layered") return shader::kFieldLayered;
  throw Error(fmt::format("voxel-paths: unknown field '{}' (none|marble|layered)", name));
}

std::vector<glm::vec4> coefficient_field(const VoxelGrid& grid, std::span<const std::uint32_t> labels,
                                         std::span<const shader::FieldMaterialGPU> materials,
                                         const FieldSettings& settings) {
  std::vector<glm::vec4> out(grid.voxel_count(), glm::vec4(0.0f));
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (labels[i] == 0) continue;
    const shader::FieldMaterialGPU& material = materials[labels[i]];
    float m = shader::field_multiplier(settings.field, grid.center(grid.voxel(i)), glm::vec3(material.lower),
                                       glm::vec3(material.upper), settings.scale, settings.contrast);
    out[i] = glm::vec4(shader::field_coefficient(material, m), 0.0f);
  }
  return out;
}

CoefficientField::CoefficientField()
    : program_(gpu::ShaderProgram::compute("voxel_paths/fill_coefficients.comp", shader_defines())) {
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
}

void CoefficientField::fill(const VoxelGrid& grid, GLuint labels_buffer,
                            std::span<const shader::FieldMaterialGPU> materials, const FieldSettings& settings) {
  gpu::DebugGroup group("voxel_field");
  static_assert(sizeof(shader::FieldMaterialGPU) == 80);
  glNamedBufferData(materials_, static_cast<GLsizeiptr>(std::max<std::size_t>(1, materials.size()) * 80),
                    materials.empty() ? nullptr : materials.data(), GL_DYNAMIC_DRAW);
  if (grid.voxel_count() != voxel_count_) {
    voxel_count_ = grid.voxel_count();
    glNamedBufferData(coefficients_, static_cast<GLsizeiptr>(voxel_count_ * 16), nullptr, GL_DYNAMIC_DRAW);
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingLabels, labels_buffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingSigmaT, coefficients_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingFieldMaterials, materials_);
  const GLuint p = program_.id();
  glUseProgram(p);
  glUniform3fv(glGetUniformLocation(p, "u_origin"), 1, &grid.origin.x);
  glUniform1f(glGetUniformLocation(p, "u_voxel_size"), grid.voxel_size);
  glUniform1i(glGetUniformLocation(p, "u_resolution"), grid.resolution);
  glUniform1i(glGetUniformLocation(p, "u_field"), settings.field);
  glUniform1f(glGetUniformLocation(p, "u_scale"), settings.scale);
  glUniform1f(glGetUniformLocation(p, "u_contrast"), settings.contrast);
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
