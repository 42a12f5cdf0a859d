// voxel_grid.cpp: see voxel_grid.h.
#include "methods/voxel_paths/voxel_grid.h"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent::methods::voxel_paths {

VoxelGrid grid_around(glm::vec3 lower, glm::vec3 upper, int resolution, int padding_voxels) {
  glm::vec3 extent = upper - lower;
  float side = std::max({extent.x, extent.y, extent.z, 1e-6f});
  int inner = std::max(1, resolution - 2 * padding_voxels);
  VoxelGrid grid;
  grid.resolution = resolution;
  grid.voxel_size = side / static_cast<float>(inner);
  grid.origin = 0.5f * (lower + upper) - 0.5f * grid.voxel_size * static_cast<float>(resolution);
  return grid;
}

TranslucentTriangles gather_translucent_triangles(const Scene& scene, bool effective_transport) {
  TranslucentTriangles out;
  out.sigma_t.assign(scene.objects.size() + 1, glm::vec4(0.0f));
  out.materials.assign(scene.objects.size() + 1, shader::FieldMaterialGPU{});
  glm::vec3 lower(std::numeric_limits<float>::max()), upper(-std::numeric_limits<float>::max());
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    if (!object.translucent()) continue;
    auto label = static_cast<std::uint32_t>(i + 1);
    // Coefficients are in mm^-1; one scene unit is scale_mm millimetres.
    glm::vec3 sigma = effective_transport ? object.material->sigma_tr() : object.material->sigma_t();
    out.sigma_t[label] = glm::vec4(sigma * scene.scale_mm, 0.0f);
    shader::FieldMaterialGPU& field = out.materials[label];
    field.sigma_a = glm::vec4(object.material->sigma_a * scene.scale_mm, effective_transport ? 1.0f : 0.0f);
    field.sigma_s = glm::vec4(object.material->sigma_s * scene.scale_mm, 0.0f);
    field.g = glm::vec4(object.material->g, 0.0f);
    const MediumField& medium = object.material->field;
    field.field = glm::vec4(static_cast<float>(medium.type), medium.scale_mm / scene.scale_mm, medium.contrast, 0.0f);
    if (medium.type == MediumFieldType::Volume) {
      if (out.volume && medium.volume && out.volume != medium.volume &&
          (out.volume->source != medium.volume->source || out.volume->values != medium.volume->values))
        throw Error(fmt::format("{}: voxel-paths supports one volume field per scene (object '{}' has a second)",
                                scene.source, object.name));
      if (!out.volume) out.volume = medium.volume;
    }
    TriangleMesh mesh = transformed(object.mesh, object.world_from_object);
    auto first = static_cast<std::uint32_t>(out.corners.size() / 3);
    glm::vec3 object_lower(std::numeric_limits<float>::max()), object_upper(-std::numeric_limits<float>::max());
    for (std::uint32_t index : mesh.indices) {
      glm::vec3 p = mesh.positions[index];
      out.corners.emplace_back(p, static_cast<float>(label));
      object_lower = glm::min(object_lower, p), object_upper = glm::max(object_upper, p);
    }
    const MediumField& medium_field = object.material->field;
    field.lower = glm::vec4(medium_field.has_bounds ? medium_field.bounds_lower : object_lower, 0.0f);
    field.upper = glm::vec4(medium_field.has_bounds ? medium_field.bounds_upper : object_upper, 0.0f);
    lower = glm::min(lower, object_lower), upper = glm::max(upper, object_upper);
    out.objects.push_back({first, static_cast<std::uint32_t>(mesh.indices.size() / 3), label});
  }
  if (!out.corners.empty()) out.lower = lower, out.upper = upper;
  return out;
}

std::string shader_defines() {
  return fmt::format(
      "#define VOXEL_BINDING_TRIANGLES {}\n#define VOXEL_BINDING_FLIPS {}\n#define VOXEL_BINDING_LABELS {}\n"
      "#define VOXEL_BINDING_DISTANCES {}\n#define VOXEL_BINDING_SIGMA_T {}\n#define VOXEL_BINDING_CHANGED {}\n"
      "#define VOXEL_BINDING_FIELD_MATERIALS {}\n#define VOXEL_BINDING_INDICES {}\n#define VOXEL_TEXTURE_VOLUME {}\n"
      "#define VOXEL_BINDING_BLOCKS_IN {}\n#define VOXEL_BINDING_BLOCKS_OUT {}\n#define VOXEL_UNREACHED {:.1e}\n"
      "#define VOXEL_TEXTURE_RADIANCE {}\n#define VOXEL_IMAGE_RADIANCE {}\n",
      kBindingTriangles, kBindingFlips, kBindingLabels, kBindingDistances, kBindingSigmaT, kBindingChanged,
      kBindingFieldMaterials, kBindingIndices, kTextureVolume, kBindingBlocksIn, kBindingBlocksOut, kUnreached,
      kTextureRadiance, kImageRadiance);
}

}  // namespace lucent::methods::voxel_paths
