// initialize_distances.comp: voxel-paths graph initialization, step 2 of 2: lit voxels start at
// n0 = -ln(F_t P) (eq. 2), with F_t P the flux that entered the voxel (initialize_flux.comp) over its cross
// section h^2 (eq. 3's sum over the shadow-map texels in the voxel, normalised to the voxel), so that exp(-n) is
// an irradiance; every other voxel starts unreached. With `u_entry_depth` d > 0 (parameter entry_depth, in
// voxels; 0 is the paper), the light also pays the optical depth d h c(v) of the segment from the surface to the
// voxel's centre, c the voxel's own edge-cost coefficient, so a lit voxel in a dense vein starts darker.
#include "methods/voxel_paths/shaders/grid.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(std430, binding = VOXEL_BINDING_FLIPS) readonly buffer FluxBlock { uint flux[]; };
layout(std430, binding = VOXEL_BINDING_DISTANCES) writeonly buffer DistanceBlock { vec4 distances[]; };
layout(std430, binding = VOXEL_BINDING_SIGMA_T) readonly buffer CoefficientBlock { vec4 coefficients[]; };

uniform float u_flux_unit;
uniform float u_entry_depth;  // [voxels]

void main() {
  ivec3 v = ivec3(gl_GlobalInvocationID);
  if (!in_grid(v)) return;
  int index = voxel_index(v);
  vec3 n0 = vec3(VOXEL_UNREACHED);
  for (int band = 0; band < 3; ++band) {
    uint units = flux[3 * index + band];
    if (units != 0u)
      n0[band] = -log(float(units) * u_flux_unit / (u_voxel_size * u_voxel_size)) +
                 u_entry_depth * u_voxel_size * coefficients[index][band];
  }
  distances[index] = vec4(n0, 0.0f);
}
