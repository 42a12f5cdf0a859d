// initialize_flux.comp: voxel-paths graph initialization, step 1 of 2 (paper Section 2.1, eqs. 2-3): every texel
// of a directional light's G-buffer layer (the reflective shadow map: world position, object) that sees a
// translucent object is a small light carrying flux E_perp A_texel; the part F_t(eta, cos theta_i) that enters
// is added to the inside voxel holding the texel's surface point (the voxel half a voxel below the surface, else
// the nearest inside voxel among its 26 neighbours). Sums are fixed point (GL 4.5 has no float atomics): one unit
// is u_flux_unit [power], chosen by the CPU so that one texel adds at most 2^16 units.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/fresnel.h"
#include "voxel_paths/grid.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = VOXEL_BINDING_LABELS) readonly buffer LabelBlock { uint labels[]; };
layout(std430, binding = VOXEL_BINDING_FLIPS) buffer FluxBlock { uint flux[]; };  // 3 per voxel (rgb)

uniform int u_light;         // index into frame.lights (directional)
uniform float u_flux_unit;   // power of one fixed-point unit

int inside_voxel_near(vec3 x, vec3 n) {
  ivec3 v = voxel_of(x - 0.5f * u_voxel_size * n);
  if (in_grid(v) && labels[voxel_index(v)] != 0u) return voxel_index(v);
  int best = -1;
  float best_d2 = 1e30f;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 u = v + ivec3(dx, dy, dz);
        if (!in_grid(u) || labels[voxel_index(u)] == 0u) continue;
        vec3 d = voxel_center(u) - x;
        if (dot(d, d) < best_d2) best = voxel_index(u), best_d2 = dot(d, d);
      }
  return best;
}

void main() {
  int size = frame.sizes.y;
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= size || texel.y >= size) return;
  LightGPU light = frame.lights[u_light];
  int layer = light.views.x;
  vec4 p = texelFetch(light_position, ivec3(texel, layer), 0);
  if (p.w < 0.5f) return;
  int material = objects[int(p.w) - 1].info.x;
  if (material < 0) return;
  vec3 n = normalize(texelFetch(light_normal, ivec3(texel, layer), 0).xyz);
  float cos_i = dot(n, -light.position.xyz);
  if (cos_i <= 0.0f) return;
  int voxel = inside_voxel_near(p.xyz, n);
  if (voxel < 0) return;
  // The texel's footprint on the view plane, perpendicular to the light: flux = E_perp A_texel.
  float texel_width = frame.light_views[layer].direction.w / float(size);
  vec3 entering = fresnel_transmittance(materials[material].sigma_a.w, cos_i) * light.power.rgb * texel_width * texel_width;
  uvec3 units = uvec3(entering / u_flux_unit + 0.5f);
  for (int band = 0; band < 3; ++band)
    if (units[band] != 0u) atomicAdd(flux[3 * voxel + band], units[band]);
}
