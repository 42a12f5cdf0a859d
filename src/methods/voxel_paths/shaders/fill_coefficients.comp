// fill_coefficients.comp: voxel-paths heterogeneous media: every voxel's edge-cost coefficient (rgb) from its
// label's material and field (media/heterogeneous_field.h) at the voxel centre; 0 outside. Runs every frame
// after voxelization; relax.comp reads the result per voxel. The volume field is trilinear by texelFetch, the
// same arithmetic as MediumVolume::multiplier on the CPU.
#include "methods/voxel_paths/shaders/grid.glsl"
#include "media/heterogeneous_field.h"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(std430, binding = VOXEL_BINDING_LABELS) readonly buffer LabelBlock { uint labels[]; };
layout(std430, binding = VOXEL_BINDING_SIGMA_T) writeonly buffer CoefficientBlock { vec4 coefficients[]; };
layout(std430, binding = VOXEL_BINDING_FIELD_MATERIALS) readonly buffer MaterialBlock { FieldMaterialGPU field_materials[]; };
layout(binding = VOXEL_TEXTURE_VOLUME) uniform sampler3D u_volume;  // R32F multipliers m

float volume_multiplier(vec3 p, vec3 lower, vec3 upper) {
  ivec3 size = textureSize(u_volume, 0);
  vec3 u = volume_grid_coordinate(p, lower, upper, size);
  ivec3 c = volume_corner(u, size);
  vec3 w = u - vec3(c);
  ivec3 d = min(c + ivec3(1), size - ivec3(1));
  float x00 = mix(texelFetch(u_volume, ivec3(c.x, c.y, c.z), 0).r, texelFetch(u_volume, ivec3(d.x, c.y, c.z), 0).r, w.x);
  float x10 = mix(texelFetch(u_volume, ivec3(c.x, d.y, c.z), 0).r, texelFetch(u_volume, ivec3(d.x, d.y, c.z), 0).r, w.x);
  float x01 = mix(texelFetch(u_volume, ivec3(c.x, c.y, d.z), 0).r, texelFetch(u_volume, ivec3(d.x, c.y, d.z), 0).r, w.x);
  float x11 = mix(texelFetch(u_volume, ivec3(c.x, d.y, d.z), 0).r, texelFetch(u_volume, ivec3(d.x, d.y, d.z), 0).r, w.x);
  return mix(mix(x00, x10, w.y), mix(x01, x11, w.y), w.z);
}

void main() {
  ivec3 v = ivec3(gl_GlobalInvocationID);
  if (!in_grid(v)) return;
  int index = voxel_index(v);
  uint label = labels[index];
  vec3 c = vec3(0.0f);
  if (label != 0u) {
    FieldMaterialGPU material = field_materials[label];
    int type = int(material.field.x);
    vec3 p = voxel_center(v);
    float m = type == kFieldVolume
                  ? volume_multiplier(p, material.lower.xyz, material.upper.xyz)
                  : field_multiplier(type, p, material.lower.xyz, material.upper.xyz, material.field.y, material.field.z);
    c = field_coefficient(material, m);
  }
  coefficients[index] = vec4(c, 0.0f);
}
