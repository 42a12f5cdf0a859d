// mesh.h: triangle meshes: loaded from files through assimp or built procedurally.
#pragma once
#include <cstdint>
#include <string>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

// An indexed triangle mesh with per-vertex unit normals, counter-clockwise front faces, normals pointing out.
struct TriangleMesh {
  std::vector<glm::vec3> positions;  // object space [scene units]
  std::vector<glm::vec3> normals;    // unit length, one per position
  std::vector<std::uint32_t> indices;  // three per triangle
  // Texture coordinates, one per position, or empty when the mesh has none. OpenGL convention: (0, 0) is the
  // bottom left of an image. Procedural shapes lay out [0, 1]^2 without overlap (vertices are duplicated along
  // seams); a loaded mesh has what its file has (channel 0, any range).
  std::vector<glm::vec2> uvs;
  // The texture coordinates a textured material's maps are read through, where `uvs` hold another
  // parametrization (a texture atlas: texture_space::with_atlas_meshes); empty: `uvs` are the material's too.
  std::vector<glm::vec2> material_uvs;
  const std::vector<glm::vec2>& map_uvs() const { return material_uvs.empty() ? uvs : material_uvs; }
};

// Loads every mesh of a file (OBJ, PLY, glTF 2.0, STL, 3DS and the other formats assimp reads) into one mesh,
// with node transforms applied. Smooth normals are generated where the file has none. Texture coordinates are
// read from channel 0 when every triangle mesh of the file has one; when only some have, none are kept (one
// warning line). Throws lucent::Error naming the file when it is missing, unreadable, or holds no triangles.
TriangleMesh load_mesh(const std::string& path);

// Procedural shapes centred at the origin, with texture coordinates in [0, 1]^2 where no two triangles overlap.
TriangleMesh make_sphere(float radius, int rings, int segments);
TriangleMesh make_torus(float major_radius, float minor_radius, int rings, int segments);
TriangleMesh make_box(glm::vec3 size);    // full edge lengths
TriangleMesh make_plane(glm::vec2 size);  // in the xz plane, normal +y
// A closed profile polygon of (r, y) points (r >= 0) revolved about the y axis: candles, cups, lamp shades.
TriangleMesh make_lathe(std::span<const glm::vec2> profile, int segments, float crease_deg = 35.0f);
// A hollow sphere: the shell between inner_radius and radius.
TriangleMesh make_shell(float radius, float inner_radius, int segments);

// Throws lucent::Error("<what>: ...") when the mesh has no triangles, an index out of range, a NaN or
// infinite coordinate or texture coordinate, texture coordinates that are not one per position, or zero total
// area.
void validate_mesh(const TriangleMesh& mesh, const std::string& what);

// Total surface area [scene units^2].
float surface_area(const TriangleMesh& mesh);

// The mesh with positions transformed by `world_from_object` and normals by its inverse transpose
// (renormalised); indices and texture coordinates unchanged. Used by the GPU upload and by the CPU references, so both see the same world-space geometry.
TriangleMesh transformed(const TriangleMesh& mesh, const glm::mat4& world_from_object);

}  // namespace lucent
