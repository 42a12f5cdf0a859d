// texture_gbuffer.cpp: see texture_gbuffer.h.
#include "texture_space/texture_gbuffer.h"

#include <algorithm>
#include <cstdint>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "gpu/image_texture.h"
#include "lucent/error.h"
#include "render/scene_gpu.h"

namespace lucent::texture_space {
namespace {

std::string shader_defines() {
  return fmt::format("#define TEXTURE_SPACE_BINDING_VERTICES {}\n#define TEXTURE_SPACE_BINDING_INDICES {}\n"
                     "#define TEXTURE_SPACE_BINDING_CORNER_UVS {}\n",
                     kBindingVertices, kBindingIndices, kBindingCornerUvs);
}

// Atlas coordinates per corner of the scene's index buffer, at the translucent meshes' ranges.
std::vector<glm::vec2> corner_uvs(const render::SceneGpu& scene_gpu, const SceneAtlas& atlas) {
  std::vector<glm::vec2> out;
  for (const render::SceneGpu::MeshRange& range : scene_gpu.translucent_meshes()) {
    auto it = std::find(atlas.object_index.begin(), atlas.object_index.end(), range.object);
    if (it == atlas.object_index.end())
      throw Error(fmt::format("texture-space G-buffer: translucent object {} is not in the atlas", range.object));
    const TriangleMesh& mesh = atlas.atlas.objects[static_cast<std::size_t>(it - atlas.object_index.begin())].mesh;
    if (mesh.indices.size() != range.index_count)
      throw Error(fmt::format("texture-space G-buffer: object {} has {} corners on the GPU and {} in the atlas (the "
                              "scene was not prepared with with_atlas_meshes)",
                              range.object, range.index_count, mesh.indices.size()));
    out.resize(std::max<std::size_t>(out.size(), range.first_index + range.index_count));
    for (std::size_t k = 0; k < mesh.indices.size(); ++k) out[range.first_index + k] = mesh.uvs[mesh.indices[k]];
  }
  return out;
}

std::vector<glm::vec4> read_texture(GLuint texture, int size) {
  std::vector<glm::vec4> texels(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)), texels.data());
  return texels;
}

}  // namespace

TextureGBuffer::TextureGBuffer(const render::SceneGpu& scene_gpu, const SceneAtlas& atlas)
    : size_(atlas.atlas.size),
      program_(gpu::ShaderProgram::graphics("texture_space/gbuffer.vert", "texture_space/conservative.geom",
                                            "texture_space/gbuffer.frag", shader_defines())) {
  const std::string name = "texture-space G-buffer";
  position_ = gpu::make_image_texture(size_, size_, GL_RGBA32F, name + " position");
  normal_ratio_ = gpu::make_image_texture(size_, size_, GL_RGBA32F, name + " normal and area ratio");
  depth_ = gpu::make_image_texture(size_, size_, GL_DEPTH_COMPONENT32F, name + " distance");
  glCreateFramebuffers(1, &framebuffer_);
  glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, position_, 0);
  glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT1, normal_ratio_, 0);
  glNamedFramebufferTexture(framebuffer_, GL_DEPTH_ATTACHMENT, depth_, 0);
  const GLenum draw_buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer_, 2, draw_buffers);
  gpu::label_object(GL_FRAMEBUFFER, framebuffer_, name);
  const double mib = static_cast<double>(size_) * size_ * (16 + 16 + 4) / (1024.0 * 1024.0);
  if (glGetError() == GL_OUT_OF_MEMORY)
    throw Error(fmt::format("{}: out of GPU memory for {}x{} texels ({:.1f} MiB)", name, size_, size_, mib));
  if (glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error(fmt::format("{}: framebuffer of {}x{} texels ({:.1f} MiB) incomplete", name, size_, size_, mib));
  std::vector<glm::vec2> uvs = corner_uvs(scene_gpu, atlas);
  glCreateBuffers(1, &corner_uvs_);
  glNamedBufferStorage(corner_uvs_, static_cast<GLsizeiptr>(std::max<std::size_t>(1, uvs.size()) * sizeof(glm::vec2)),
                       uvs.empty() ? nullptr : uvs.data(), 0);
  gpu::label_object(GL_BUFFER, corner_uvs_, name + " corner uvs");
  glCreateVertexArrays(1, &vao_);  // no attributes: the vertex shader reads the buffers
  gpu::label_object(GL_VERTEX_ARRAY, vao_, name);
}

TextureGBuffer::~TextureGBuffer() {
  glDeleteFramebuffers(1, &framebuffer_);
  GLuint textures[] = {position_, normal_ratio_, depth_};
  glDeleteTextures(3, textures);
  glDeleteBuffers(1, &corner_uvs_);
  glDeleteVertexArrays(1, &vao_);
}

void TextureGBuffer::render(const render::SceneGpu& scene_gpu) {
  gpu::DebugGroup group("texture_gbuffer");
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, size_, size_);
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, far = 1.0f;
  glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 1, zero);
  glClearNamedFramebufferfv(framebuffer_, GL_DEPTH, 0, &far);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingVertices, scene_gpu.vertex_buffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingIndices, scene_gpu.index_buffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingCornerUvs, corner_uvs_);
  glBindVertexArray(vao_);
  const GLuint program = program_.id();
  glUseProgram(program);
  glUniform1f(glGetUniformLocation(program, "u_size"), static_cast<float>(size_));
  for (const render::SceneGpu::MeshRange& range : scene_gpu.translucent_meshes()) {
    glUniform1ui(glGetUniformLocation(program, "u_first_index"), range.first_index);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(range.index_count));
  }
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void TextureGBuffer::bind_textures(int position_unit, int normal_unit) const {
  glBindTextureUnit(static_cast<GLuint>(position_unit), position_);
  glBindTextureUnit(static_cast<GLuint>(normal_unit), normal_ratio_);
}

std::vector<glm::vec4> TextureGBuffer::read_position() const { return read_texture(position_, size_); }
std::vector<glm::vec4> TextureGBuffer::read_normal_ratio() const { return read_texture(normal_ratio_, size_); }

}  // namespace lucent::texture_space
