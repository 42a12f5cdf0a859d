// radiance.comp: voxel-paths radiance (paper Section 2.2, eq. 1 without F_t, which the shading applies for the
// view direction): exp(-n(v)) per band into an RGBA16F 3D texture that the shading interpolates trilinearly.
// Outside voxels take the mean of their reached inside neighbours, so that interpolation at the surface does not
// blend in the zero of the outside.
#include "methods/voxel_paths/shaders/grid.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(std430, binding = VOXEL_BINDING_LABELS) readonly buffer LabelBlock { uint labels[]; };
layout(std430, binding = VOXEL_BINDING_DISTANCES) readonly buffer DistanceBlock { vec4 distances[]; };
layout(rgba16f, binding = VOXEL_IMAGE_RADIANCE) uniform writeonly image3D radiance;

vec3 transmitted(int index) {
  vec3 n = distances[index].rgb;
  return mix(exp(-n), vec3(0.0f), greaterThanEqual(n, vec3(0.5f * VOXEL_UNREACHED)));
}

void main() {
  ivec3 v = ivec3(gl_GlobalInvocationID);
  if (!in_grid(v)) return;
  int index = voxel_index(v);
  vec3 L = vec3(0.0f);
  if (labels[index] != 0u) {
    L = transmitted(index);
  } else {
    float count = 0.0f;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          ivec3 u = v + ivec3(dx, dy, dz);
          if (!in_grid(u) || labels[voxel_index(u)] == 0u) continue;
          L += transmitted(voxel_index(u)), count += 1.0f;
        }
    if (count > 0.0f) L /= count;
  }
  imageStore(radiance, v, vec4(min(L, vec3(65000.0f)), 1.0f));
}
