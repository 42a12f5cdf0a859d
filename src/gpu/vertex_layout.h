// vertex_layout.h: the vertex array layout of shader::VertexGPU (shared/shader_io.h), for every VAO that draws
// such vertices: attribute 0 position (xyz world, w object index), 1 normal, 2 texture coordinates (xy).
#pragma once
#include <cstddef>

#include <epoxy/gl.h>

#include "shared/shader_io.h"

namespace lucent::gpu {

inline constexpr GLuint kVertexPositionAttribute = 0, kVertexNormalAttribute = 1, kVertexUvAttribute = 2;

// Binds `buffer` (VertexGPU[]) to binding 0 of `vao` and enables the three vec4 attributes.
inline void set_vertex_gpu_layout(GLuint vao, GLuint buffer) {
  using shader::VertexGPU;
  glVertexArrayVertexBuffer(vao, 0, buffer, 0, sizeof(VertexGPU));
  const struct {
    GLuint attribute;
    std::size_t offset;
  } attributes[] = {{kVertexPositionAttribute, offsetof(VertexGPU, position)},
                    {kVertexNormalAttribute, offsetof(VertexGPU, normal)},
                    {kVertexUvAttribute, offsetof(VertexGPU, uv)}};
  for (const auto& a : attributes) {
    glEnableVertexArrayAttrib(vao, a.attribute);
    glVertexArrayAttribFormat(vao, a.attribute, 4, GL_FLOAT, GL_FALSE, static_cast<GLuint>(a.offset));
    glVertexArrayAttribBinding(vao, a.attribute, 0);
  }
}

}  // namespace lucent::gpu
