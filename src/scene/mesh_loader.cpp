// mesh_loader.cpp: reads triangle meshes from files through assimp, checks meshes before they are used and
// measures their surface area. The importer runs in a child process (scene/import_guard.h), after a size check
// of PLY headers (scene/ply_size_check.h); what it returns is validated before anything uses it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "io/file_path_check.h"
#include "io/printable_text.h"
#include "lucent/warning.h"
#include "lucent/error.h"
#include "lucent/output_file.h"
#include "io/input_file.h"
#include "lucent/mesh.h"
#include "scene/gltf_file_check.h"
#include "scene/import_guard.h"
#include "scene/mesh_loader.h"
#include "scene/ply_size_check.h"

namespace lucent {
namespace {

glm::vec3 to_glm(const aiVector3D& v) { return {v.x, v.y, v.z}; }

bool is_finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool is_finite(glm::vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

// Twice the area of triangle t, pointing along its front side (counter-clockwise).
glm::vec3 area_vector(const TriangleMesh& mesh, std::size_t t) {
  glm::vec3 p0 = mesh.positions[mesh.indices[3 * t]];
  glm::vec3 p1 = mesh.positions[mesh.indices[3 * t + 1]];
  glm::vec3 p2 = mesh.positions[mesh.indices[3 * t + 2]];
  return glm::cross(p1 - p0, p2 - p0);
}

// Assimp's messages may span lines; lucent errors are one line.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

// Appends the triangles of one assimp mesh; faces that are not triangles (points, lines) are skipped. Indices
// are checked against the mesh's own vertices (after offsetting they could land on another mesh's). With
// `with_uvs`, texture channel `uv_set` (u, v; a third component is ignored) is appended too: the mesh must have it.
void append_mesh(const aiMesh& src, TriangleMesh& dst, bool with_uvs, unsigned uv_set, const std::string& path) {
  if (src.mNumVertices > std::numeric_limits<std::uint32_t>::max() - dst.positions.size())
    throw Error(path + ": cannot read mesh: more than 2^32 vertices");
  const auto base = static_cast<std::uint32_t>(dst.positions.size());
  for (unsigned i = 0; i < src.mNumVertices; ++i) {
    dst.positions.push_back(to_glm(src.mVertices[i]));
    dst.normals.push_back(src.mNormals ? to_glm(src.mNormals[i]) : glm::vec3(0.0f));
    if (with_uvs) dst.uvs.emplace_back(src.mTextureCoords[uv_set][i].x, src.mTextureCoords[uv_set][i].y);
  }
  for (unsigned f = 0; f < src.mNumFaces; ++f) {
    const aiFace& face = src.mFaces[f];
    if (face.mNumIndices != 3) continue;
    for (unsigned k = 0; k < 3; ++k) {
      if (face.mIndices[k] >= src.mNumVertices)
        throw Error(path + ": index " + std::to_string(face.mIndices[k]) + " out of range (" +
                    std::to_string(src.mNumVertices) + " vertices)");
      dst.indices.push_back(base + face.mIndices[k]);
    }
  }
}

// Normalizes the normals. A zero, NaN or infinite normal is replaced by the normal of the triangles that use
// the vertex (their area-weighted mean; the face normal when one triangle uses it). A vertex no usable
// triangle touches gets +z so that every normal stays unit length.
void repair_normals(TriangleMesh& mesh) {
  std::vector<bool> bad(mesh.normals.size());
  for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
    float len = glm::length(mesh.normals[i]);
    bad[i] = !(std::isfinite(len) && len > 0.0f);
    mesh.normals[i] = bad[i] ? glm::vec3(0.0f) : mesh.normals[i] / len;
  }
  for (std::size_t t = 0; t < mesh.indices.size() / 3; ++t) {
    glm::vec3 n = area_vector(mesh, t);
    if (!is_finite(n)) continue;
    for (std::size_t k = 0; k < 3; ++k)
      if (bad[mesh.indices[3 * t + k]]) mesh.normals[mesh.indices[3 * t + k]] += n;
  }
  for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
    if (!bad[i]) continue;
    float len = glm::length(mesh.normals[i]);
    bool usable = std::isfinite(len) && len > 0.0f;
    mesh.normals[i] = usable ? mesh.normals[i] / len : glm::vec3(0.0f, 0.0f, 1.0f);
  }
}

// The importer's triangles, as the child process builds them (normals not yet repaired).
TriangleMesh import_triangles(const std::string& path, unsigned uv_set) {
  Assimp::Importer importer;
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_GenSmoothNormals | aiProcess_PreTransformVertices | aiProcess_SortByPType;
  const aiScene* scene = importer.ReadFile(path, flags);
  if (!scene) {
    const std::string reason = one_line(importer.GetErrorString());
    // Assimp's words for a file whose meshes hold no face (a truncated OBJ, a glTF of points only).
    if (reason.find("all meshes are orphaned") != std::string::npos)
      throw Error(path + ": cannot read mesh: it holds no faces (no triangles to render; is the file truncated?)");
    throw Error(path + ": cannot read mesh: " + printable_text(reason));
  }

  // SortByPType leaves each mesh one primitive type. Point and line meshes are dropped here rather than by
  // AI_CONFIG_PP_SBP_REMOVE, which fails a file of lines alone as "No meshes remaining".
  std::vector<const aiMesh*> triangle_meshes;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
    if (scene->mMeshes[m]->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) triangle_meshes.push_back(scene->mMeshes[m]);
  // Texture coordinates are all or nothing: a vertex without them has no meaningful value to fill in.
  const auto textured = std::count_if(triangle_meshes.begin(), triangle_meshes.end(),
                                      [&](const aiMesh* m) { return m->HasTextureCoords(uv_set); });
  const bool with_uvs = !triangle_meshes.empty() && textured == std::ssize(triangle_meshes);
  if (textured > 0 && !with_uvs)  // printed by the importer's process, on the same stderr
    warn(fmt::format("{}: texture coordinates dropped: only {} of {} meshes have them", path, textured,
                     triangle_meshes.size()));
  TriangleMesh mesh;
  for (const aiMesh* m : triangle_meshes) append_mesh(*m, mesh, with_uvs, uv_set, path);
  return mesh;
}

}  // namespace

TriangleMesh load_mesh(const std::string& path) { return load_mesh_with_uv_set(path, 0); }

TriangleMesh load_mesh_with_uv_set(const std::string& path, unsigned uv_set) {
  check_file_path(path);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(path + ": no such file");
  require_regular_file(path);
  check_ply_size(path);
  if (const std::string extension = lowercase_extension(path); extension == ".gltf" || extension == ".glb")
    check_gltf_file(path);  // before the importer allocates

  // Address space for the importer: generous for real files (its own structures take a few times the file),
  // small enough that a header asking for terabytes fails in the child.
  ImportLimits limits = mesh_import_limits();
  const std::uintmax_t file_size = std::filesystem::file_size(path, ec);
  limits.memory_bytes = std::max<std::uint64_t>(std::uint64_t{4} << 30, ec ? 0 : 200 * std::uint64_t{file_size});
  TriangleMesh mesh = import_in_child(path, [&] { return import_triangles(path, uv_set); }, limits);

  if (mesh.indices.empty()) throw Error(path + ": the file holds no triangles");
  validate_mesh(mesh, path);
  repair_normals(mesh);
  return mesh;
}

void validate_mesh(const TriangleMesh& mesh, const std::string& what) {
  if (mesh.indices.size() < 3) throw Error(what + ": mesh has no triangles");
  if (mesh.indices.size() % 3 != 0)
    throw Error(what + ": index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
  if (mesh.normals.size() != mesh.positions.size())
    throw Error(what + ": normals count differs from positions count");
  if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size())
    throw Error(what + ": texture coordinate count " + std::to_string(mesh.uvs.size()) + " differs from vertex count " +
                std::to_string(mesh.positions.size()));
  for (std::uint32_t index : mesh.indices)
    if (index >= mesh.positions.size())
      throw Error(what + ": index " + std::to_string(index) + " out of range (" +
                  std::to_string(mesh.positions.size()) + " vertices)");
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if (!is_finite(mesh.positions[i]))
      throw Error(what + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
  for (std::size_t i = 0; i < mesh.uvs.size(); ++i)
    if (!is_finite(mesh.uvs[i]))
      throw Error(what + ": vertex " + std::to_string(i) + " has a non-finite texture coordinate");
  if (!(surface_area(mesh) > 0.0f)) throw Error(what + ": mesh has zero surface area (degenerate triangles)");
}

// Indices must be in range (validate_mesh checks them).
float surface_area(const TriangleMesh& mesh) {
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.indices.size() / 3; ++t)
    area += 0.5 * static_cast<double>(glm::length(area_vector(mesh, t)));
  return static_cast<float>(area);
}

}  // namespace lucent
