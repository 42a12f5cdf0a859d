// voxel_grid.h: the voxel grid of the voxel-paths method (Dijkstra shortest optical paths through a solid
// voxelization, "voxel-dijkstra-heterogeneous-sss", Section 2.1): R^3 cubic voxels over the translucent objects,
// the translucent triangles it is built from, and the per-voxel labels (0 outside, object index + 1 inside).
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/scene.h"
#include "media/heterogeneous_field.h"
#include "shared/bindings.h"

namespace lucent::methods::voxel_paths {

// Binding points of the voxel-paths shaders (passed to them as #defines, see shader_defines()), in the method
// ranges of shared/bindings.h. Storage buffers:
inline constexpr int kBindingTriangles = 20;  // shader::VertexGPU per vertex (the scene's vertex buffer)
inline constexpr int kBindingFlips = 21;      // uint per voxel: parity of the crossings entering at that voxel
inline constexpr int kBindingLabels = 22;     // uint per voxel: 0 outside, object index + 1 inside
inline constexpr int kBindingDistances = 23;  // vec4 per voxel: rgb optical path length n(v) per band
inline constexpr int kBindingSigmaT = 24;     // vec4 per voxel: rgb edge-cost coefficient [1/scene unit]
inline constexpr int kBindingChanged = 25;    // uint: set to 1 by a relaxation that lowered a distance
inline constexpr int kBindingFieldMaterials = 26;  // shader::FieldMaterialGPU per label
inline constexpr int kBindingIndices = 27;         // uint per triangle corner: indices into the vertices
inline constexpr int kBindingBlocksIn = 28;        // uint per 4^3 block: lowered a value in the previous sweep
inline constexpr int kBindingBlocksOut = 29;       // uint per 4^3 block: lowered a value in this sweep
// Texture units and image units:
inline constexpr int kTextureVolume = 8;     // R32F 3D texture of the scene's volume field
inline constexpr int kTextureRadiance = 9;   // RGBA16F 3D texture exp(-n) read by the shading pass
inline constexpr int kImageRadiance = 2;     // the same texture written by the radiance pass
static_assert(kBindingTriangles >= LUCENT_METHOD_STORAGE_FIRST && kBindingBlocksOut <= LUCENT_METHOD_STORAGE_LAST);
static_assert(kTextureVolume >= LUCENT_METHOD_TEX_FIRST && kTextureRadiance <= LUCENT_METHOD_TEX_LAST);
static_assert(kImageRadiance >= LUCENT_METHOD_IMAGE_FIRST && kImageRadiance <= LUCENT_METHOD_IMAGE_LAST);

// Distances at or above this are "not reached" (outside voxels, or no path from a lit voxel).
inline constexpr float kUnreached = 1.0e30f;

struct VoxelGrid {
  int resolution = 64;         // R voxels per axis
  glm::vec3 origin{0.0f};      // corner of voxel (0, 0, 0) [scene units]
  float voxel_size = 1.0f;     // h, edge length [scene units]

  std::size_t voxel_count() const {
    return static_cast<std::size_t>(resolution) * static_cast<std::size_t>(resolution) *
           static_cast<std::size_t>(resolution);
  }
  // x fastest, then y, then z.
  std::size_t index(glm::ivec3 v) const {
    return (static_cast<std::size_t>(v.z) * static_cast<std::size_t>(resolution) + static_cast<std::size_t>(v.y)) *
               static_cast<std::size_t>(resolution) +
           static_cast<std::size_t>(v.x);
  }
  glm::ivec3 voxel(std::size_t index) const {
    const auto r = static_cast<std::size_t>(resolution);
    return {static_cast<int>(index % r), static_cast<int>((index / r) % r), static_cast<int>(index / (r * r))};
  }
  glm::vec3 center(glm::ivec3 v) const { return origin + (glm::vec3(v) + 0.5f) * voxel_size; }
};

// The cube of R^3 voxels whose side is the largest extent of [lower, upper], centred on it, grown by
// `padding_voxels` on every side (so that surface voxels have outside neighbours).
VoxelGrid grid_around(glm::vec3 lower, glm::vec3 upper, int resolution, int padding_voxels);

// The translucent objects' triangles in world space, three vec4 per triangle (w: object index + 1), one
// contiguous range per object, and each label's path-cost coefficient in scene units: sigma_t (the paper), or
// with `effective_transport` the diffusion's sigma_tr = sqrt(3 sigma_a sigma_t'), which carries absorption.
struct TranslucentTriangles {
  std::vector<glm::vec4> corners;
  struct Range {
    std::uint32_t first_triangle, triangle_count, label;
  };
  std::vector<Range> objects;
  std::vector<glm::vec4> sigma_t;  // per label (index 0: outside, zero); rgb cost coefficient [1/scene unit]
  std::vector<shader::FieldMaterialGPU> materials;  // per label: the same material, bounds and field
  std::shared_ptr<const MediumVolume> volume;        // the (single) volume field of the scene, if any
  glm::vec3 lower{0.0f}, upper{0.0f};  // world-space bounds of all corners
};
TranslucentTriangles gather_translucent_triangles(const Scene& scene, bool effective_transport = false);

// "#define VOXEL_BINDING_... n" lines for the shaders.
std::string shader_defines();

}  // namespace lucent::methods::voxel_paths
