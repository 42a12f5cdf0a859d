// mesh_transform.cpp: object-space meshes to world space, shared by the GPU upload and the CPU references.
#include "lucent/mesh.h"

namespace lucent {

TriangleMesh transformed(const TriangleMesh& mesh, const glm::mat4& world_from_object) {
  glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(world_from_object)));
  TriangleMesh out;
  out.indices = mesh.indices;
  out.uvs = mesh.uvs;  // texture space does not move with the object
  out.material_uvs = mesh.material_uvs;
  out.positions.reserve(mesh.positions.size());
  out.normals.reserve(mesh.normals.size());
  for (const glm::vec3& p : mesh.positions) out.positions.push_back(glm::vec3(world_from_object * glm::vec4(p, 1.0f)));
  for (const glm::vec3& n : mesh.normals) out.normals.push_back(glm::normalize(normal_matrix * n));
  return out;
}

}  // namespace lucent
