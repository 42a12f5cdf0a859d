// scene_gpu.cpp: uploads a scene: world-space vertices, indices, materials in scene units, objects.
#include "render/scene_gpu.h"

#include <algorithm>
#include <numeric>

#include "geometry/blob_field.h"
#include "geometry/blob_isosurface.h"
#include "geometry/isosurface_grid.h"
#include "geometry/thickness_grid.h"
#include "gpu/gl_debug.h"
#include "gpu/frame_profiler.h"
#include "gpu/vertex_layout.h"
#include "lucent/error.h"
#include <fmt/format.h>

#include "materials/tabulated_bssrdf.h"
#include "shared/shader_io.h"

namespace lucent::render {
namespace {

using shader::MaterialGPU;
using shader::ObjectGPU;
using shader::VertexGPU;

BoundingSphere bounds_of(const std::vector<glm::vec3>& points) {
  if (points.empty()) return {};
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  BoundingSphere sphere{0.5f * (lo + hi), 0.0f};
  for (const glm::vec3& p : points) sphere.radius = std::max(sphere.radius, glm::length(p - sphere.center));
  return sphere;
}

// A map's texels appended to `texels` (scaled by `scale`); its descriptor (first texel, width, height).
glm::ivec4 append_map(const std::vector<glm::vec3>& values, glm::ivec2 size, float scale, std::vector<glm::vec4>& texels) {
  if (values.empty()) return glm::ivec4(-1, 0, 0, 0);
  const glm::ivec4 map(static_cast<int>(texels.size()), size.x, size.y, 0);
  for (const glm::vec3& v : values) texels.emplace_back(v * scale, 0.0f);
  return map;
}

MaterialGPU to_gpu(const Material& m, float scale_mm, std::vector<glm::vec4>& map_texels) {
  // Coefficients are in mm^-1; one scene unit is scale_mm millimetres.
  MaterialGPU out;
  out.sigma_a = glm::vec4(m.sigma_a * scale_mm, m.eta);
  out.sigma_s = glm::vec4(m.sigma_s * scale_mm, static_cast<float>(static_cast<int>(m.model)));
  out.g = glm::vec4(m.g, m.thickness_mm / scale_mm);  // [scene units]
  out.alpha_map = out.mfp_map = glm::ivec4(-1, 0, 0, 0);
  if (m.maps) {
    out.alpha_map = append_map(m.maps->alpha, m.maps->alpha_size, 1.0f, map_texels);
    out.mfp_map = append_map(m.maps->mfp_mm, m.maps->mfp_size, 1.0f / scale_mm, map_texels);  // [scene units]
  }
  return out;
}

// Vertex v of a world-space mesh (texture coordinates 0 where it has none): xy the mesh's texture coordinates
// (an atlas's, for texture-space methods), zw those a textured material's maps are read through.
VertexGPU to_gpu(const TriangleMesh& world, std::size_t v, std::size_t object) {
  glm::vec2 uv = world.uvs.empty() ? glm::vec2(0.0f) : world.uvs[v];
  glm::vec2 map_uv = world.map_uvs().empty() ? glm::vec2(0.0f) : world.map_uvs()[v];
  return {glm::vec4(world.positions[v], static_cast<float>(object)), glm::vec4(world.normals[v], 0.0f),
          glm::vec4(uv, map_uv)};
}

template <typename T>
GLuint make_buffer(const std::vector<T>& data, const char* label, GLbitfield flags = 0) {
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(std::max<std::size_t>(1, data.size()) * sizeof(T)),
                       data.empty() ? nullptr : data.data(), flags);
  gpu::label_object(GL_BUFFER, buffer, label);
  return buffer;
}

// The object's ObjectGPU.info: its material's index (-1: opaque) and the first texel of its thickness grid in the
// material map buffer (-1: none), appended to `texels` here.
glm::ivec4 object_info(const SceneObject& object, int material, std::vector<glm::vec4>& texels) {
  const bool grid = object.translucent() && !object.thickness.empty();
  return glm::ivec4(material, grid ? append_thickness_grid(object.thickness, texels) : -1, 0, 0);
}

}  // namespace

SceneGpu::SceneGpu(const Scene& scene, bool model_tables) : model_tables_(model_tables) {
  std::vector<std::size_t> order(scene.objects.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_partition(order.begin(), order.end(), [&](std::size_t i) { return scene.objects[i].translucent(); });

  std::vector<VertexGPU> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<MaterialGPU> materials;
  std::vector<glm::vec4> map_texels;
  std::vector<ObjectGPU> objects(scene.objects.size());
  std::vector<glm::vec3> all_points, translucent_points;
  for (std::size_t i : order) {
    const SceneObject& object = scene.objects[i];
    auto add_bounds = [&](const std::vector<glm::vec3>& points) {
      all_points.insert(all_points.end(), points.begin(), points.end());
      if (object.translucent()) translucent_points.insert(translucent_points.end(), points.begin(), points.end());
    };
    if (object.blob_resolution > 0) {
      // Extracted on the GPU each frame; bounded by the field's provable box (world space, no transform).
      blobs_.push_back(std::make_unique<geometry::BlobIsosurface>(geometry::blob_grid(object.blob_resolution),
                                                                  static_cast<int>(i)));
      if (object.translucent()) ++translucent_blob_count_;
      glm::vec3 b = shader::blob_body_bound();
      std::vector<glm::vec3> corners;
      for (int c = 0; c < 8; ++c) corners.emplace_back(c & 1 ? b.x : -b.x, c & 2 ? b.y : -b.y, c & 4 ? b.z : -b.z);
      add_bounds(corners);
    } else {
      TriangleMesh world = transformed(object.mesh, object.world_from_object);
      auto base = static_cast<std::uint32_t>(vertices.size());
      for (std::size_t v = 0; v < world.positions.size(); ++v) vertices.push_back(to_gpu(world, v, i));
      if (object.translucent())
        translucent_meshes_.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(indices.size()),
                                       static_cast<std::uint32_t>(object.mesh.indices.size())});
      for (std::uint32_t index : object.mesh.indices) indices.push_back(base + index);
      add_bounds(world.positions);
      if (object.deformation.type != DeformationType::None) {
        deforming_.push_back({i, base, object.mesh, object.world_from_object, object.deformation});
        // Conservative bounds: the deformed mesh sampled over one period.
        for (int k = 0; k < 24; ++k)
          add_bounds(transformed(deformed_mesh(object.mesh, object.deformation, double(object.deformation.period_s) * k / 24.0),
                                 object.world_from_object).positions);
      }
    }
    if (object.translucent()) {
      translucent_index_count_ = static_cast<GLsizei>(indices.size());
      objects[i].info = object_info(object, static_cast<int>(materials.size()), map_texels);
      materials.push_back(to_gpu(*object.material, scene.scale_mm, map_texels));
    } else {
      objects[i].info = object_info(object, -1, map_texels);
    }
    objects[i].albedo = glm::vec4(object.albedo, 1.0f);
  }
  index_count_ = static_cast<GLsizei>(indices.size());
  scene_bounds_ = bounds_of(all_points);
  translucent_bounds_ = translucent_points.empty() ? scene_bounds_ : bounds_of(translucent_points);
  const std::vector<glm::vec3>& box_points = translucent_points.empty() ? all_points : translucent_points;
  translucent_lower_ = glm::vec3(1e30f), translucent_upper_ = glm::vec3(-1e30f);
  for (const glm::vec3& p : box_points)
    translucent_lower_ = glm::min(translucent_lower_, p), translucent_upper_ = glm::max(translucent_upper_, p);
  if (box_points.empty()) translucent_lower_ = translucent_upper_ = glm::vec3(0.0f);
  if (!deforming_.empty()) {  // sampled over time: a little margin for the instants between samples
    scene_bounds_.radius *= 1.02f;
    translucent_bounds_.radius *= 1.02f;
    const glm::vec3 margin = 0.01f * (translucent_upper_ - translucent_lower_);
    translucent_lower_ -= margin, translucent_upper_ += margin;
  }
  // blobs_ follows `order`, so translucent blobs come first, as draw_translucent() expects.

  vertex_bytes_ = vertices.size() * sizeof(VertexGPU);
  vertex_buffer_ = make_buffer(vertices, "scene vertices", deforming_.empty() ? 0 : GL_DYNAMIC_STORAGE_BIT);
  index_buffer_ = make_buffer(indices, "scene indices");
  material_buffer_ = make_buffer(materials, "materials", GL_DYNAMIC_STORAGE_BIT);
  object_buffer_ = make_buffer(objects, "objects", GL_DYNAMIC_STORAGE_BIT);
  material_count_ = materials.size();
  upload_material_maps(map_texels, scene.source);
  for (const SceneObject& object : scene.objects)
    if (object.translucent() && model_tables_) prepare_bssrdf_tables(*object.material);
  upload_bssrdf_tables();
  glCreateVertexArrays(1, &vao_);
  gpu::set_vertex_gpu_layout(vao_, vertex_buffer_);
  glVertexArrayElementBuffer(vao_, index_buffer_);
  gpu::label_object(GL_VERTEX_ARRAY, vao_, "scene");
}

SceneGpu::~SceneGpu() {
  GLuint buffers[] = {vertex_buffer_, index_buffer_, material_buffer_, object_buffer_, bssrdf_table_buffer_,
                      material_map_buffer_};
  glDeleteBuffers(6, buffers);
  glDeleteVertexArrays(1, &vao_);
}

void SceneGpu::upload_bssrdf_tables() {
  if (bssrdf_table_buffer_ != 0 && bssrdf_table_generation_ == bssrdf_table_generation()) return;
  bssrdf_table_generation_ = bssrdf_table_generation();
  if (bssrdf_table_buffer_ != 0) glDeleteBuffers(1, &bssrdf_table_buffer_);
  bssrdf_table_buffer_ = make_buffer(bssrdf_table_array(), "bssrdf tables");
}

void SceneGpu::upload_material_maps(const std::vector<glm::vec4>& texels, const std::string& source) {
  const std::uint64_t bytes = texels.size() * sizeof(glm::vec4);
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  if (bytes > static_cast<std::uint64_t>(max_block))
    throw Error(fmt::format("{}: the material maps' {} texels take {:.1f} MiB on the GPU, more than this driver's "
                            "largest storage block ({:.1f} MiB); use smaller maps",
                            source, texels.size(), static_cast<double>(bytes) / 1048576.0,
                            static_cast<double>(max_block) / 1048576.0));
  material_map_bytes_ = bytes;
  if (material_map_buffer_ != 0) glDeleteBuffers(1, &material_map_buffer_);
  material_map_buffer_ = make_buffer(texels, "material maps");  // one unused texel when no material has maps
}

void SceneGpu::bind_buffers() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_MATERIAL_MAPS, material_map_buffer_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_BSSRDF_TABLES, bssrdf_table_buffer_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_MATERIALS, material_buffer_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_OBJECTS, object_buffer_);
}

void SceneGpu::draw_all(int instances) const {
  if (instances <= 0) return;
  glBindVertexArray(vao_);
  if (index_count_ > 0) glDrawElementsInstanced(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr, instances);
  for (const auto& blob : blobs_) blob->draw(instances);
}

void SceneGpu::draw_translucent(int instances) const {
  if (instances <= 0) return;
  glBindVertexArray(vao_);
  if (translucent_index_count_ > 0)
    glDrawElementsInstanced(GL_TRIANGLES, translucent_index_count_, GL_UNSIGNED_INT, nullptr, instances);
  for (std::size_t b = 0; b < translucent_blob_count_; ++b) blobs_[b]->draw(instances);
}

void SceneGpu::update(double seconds, gpu::FrameProfiler* profiler) {
  for (const Deforming& d : deforming_) {
    TriangleMesh world = transformed(deformed_mesh(d.mesh, d.deformation, seconds), d.world_from_object);
    std::vector<VertexGPU> vertices(world.positions.size());
    for (std::size_t v = 0; v < vertices.size(); ++v) vertices[v] = to_gpu(world, v, d.object);
    glNamedBufferSubData(vertex_buffer_, static_cast<GLintptr>(d.first_vertex * sizeof(VertexGPU)),
                         static_cast<GLsizeiptr>(vertices.size() * sizeof(VertexGPU)), vertices.data());
  }
  for (const auto& blob : blobs_) blob->extract(static_cast<float>(seconds), profiler);
}

void SceneGpu::update_materials(const Scene& scene) {
  std::vector<MaterialGPU> materials;
  std::vector<glm::vec4> map_texels;
  std::vector<ObjectGPU> objects(scene.objects.size());
  // Same order as the constructor: translucent objects first.
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      const SceneObject& object = scene.objects[i];
      if (object.translucent() != (pass == 0)) continue;
      objects[i].info = object_info(object, object.translucent() ? static_cast<int>(materials.size()) : -1, map_texels);
      objects[i].albedo = glm::vec4(object.albedo, 1.0f);
      if (object.translucent()) materials.push_back(to_gpu(*object.material, scene.scale_mm, map_texels));
    }
  if (materials.size() != material_count_)
    throw Error("SceneGpu::update_materials: the translucent objects changed; rebuild the scene instead");
  for (const SceneObject& object : scene.objects)
    if (object.translucent() && model_tables_) prepare_bssrdf_tables(*object.material);
  upload_bssrdf_tables();  // callers bind the buffers again before drawing
  upload_material_maps(map_texels, scene.source);
  if (!materials.empty())
    glNamedBufferSubData(material_buffer_, 0, static_cast<GLsizeiptr>(materials.size() * sizeof(MaterialGPU)),
                         materials.data());
  if (!objects.empty())
    glNamedBufferSubData(object_buffer_, 0, static_cast<GLsizeiptr>(objects.size() * sizeof(ObjectGPU)), objects.data());
}

std::size_t SceneGpu::gpu_memory_bytes() const {
  std::size_t bytes = vertex_bytes_ + static_cast<std::size_t>(index_count_) * 4 + material_map_bytes_;
  for (const auto& blob : blobs_) bytes += blob->gpu_memory_bytes();
  return bytes;
}

}  // namespace lucent::render
