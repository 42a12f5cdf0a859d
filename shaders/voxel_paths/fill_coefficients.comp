// fill_coefficients.comp: voxel-paths heterogeneous media: every voxel's edge-cost coefficient (rgb) from its
// label's material and the field of methods/voxel_paths/heterogeneous_field.h at the voxel centre; 0 outside.
// Runs every frame after voxelization; relax.comp reads the result per voxel.
#include "voxel_paths/grid.glsl"
#include "methods/voxel_paths/heterogeneous_field.h"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(std430, binding = VOXEL_BINDING_LABELS) readonly buffer LabelBlock { uint labels[]; };
layout(std430, binding = VOXEL_BINDING_SIGMA_T) writeonly buffer CoefficientBlock { vec4 coefficients[]; };
layout(std430, binding = VOXEL_BINDING_FIELD_MATERIALS) readonly buffer MaterialBlock { FieldMaterialGPU field_materials[]; };

uniform int u_field;       // kField*
uniform float u_scale;     // feature size [scene units]
uniform float u_contrast;  // m in [1, 1 + contrast]

void main() {
  ivec3 v = ivec3(gl_GlobalInvocationID);
  if (!in_grid(v)) return;
  int index = voxel_index(v);
  uint label = labels[index];
  vec3 c = vec3(0.0f);
  if (label != 0u) {
    FieldMaterialGPU material = field_materials[label];
    float m = field_multiplier(u_field, voxel_center(v), material.lower.xyz, material.upper.xyz, u_scale, u_contrast);
    c = field_coefficient(material, m);
  }
  coefficients[index] = vec4(c, 0.0f);
}
