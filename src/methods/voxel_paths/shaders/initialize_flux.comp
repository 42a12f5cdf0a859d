// initialize_flux.comp: voxel-paths graph initialization, step 1 of 2 (paper Section 2.1, eqs. 2-3): every texel
// of a light's G-buffer layers framing the translucent objects (the reflective shadow map: world position,
// object) that sees a translucent object is a small light carrying a power P: directional, E_perp A_texel (the
// texel's footprint on the view plane); point and spot, irradiance I cone cos_i / d^2 times the texel's surface
// area d^2 d_omega / cos_i, i.e. P = I cone d_omega (d_omega the texel's solid angle, below). The part
// F_t(eta, cos theta_i) that enters is added to the inside voxel holding the texel's surface point (the voxel half a voxel below the surface, else
// the nearest inside voxel among its 26 neighbours). Sums are fixed point (GL 4.5 has no float atomics): one unit
// is u_flux_unit [power], chosen by the CPU so that one texel adds at most 2^16 units.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/fresnel.h"
#include "methods/voxel_paths/shaders/grid.glsl"

layout(local_size_x = 8, local_size_y = 8) in;  // z: the layer among the light's views.y layers

layout(std430, binding = VOXEL_BINDING_LABELS) readonly buffer LabelBlock { uint labels[]; };
layout(std430, binding = VOXEL_BINDING_FLIPS) buffer FluxBlock { uint flux[]; };  // 3 per voxel (rgb)

uniform int u_light;         // index into frame.lights
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
  int size = frame.light_counts.z;
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= size || texel.y >= size) return;
  LightGPU light = frame.lights[u_light];
  if (int(gl_GlobalInvocationID.z) >= light.views.y) return;
  int layer = light.views.x + int(gl_GlobalInvocationID.z);
  vec4 p = texelFetch(light_position, ivec3(texel, layer), 0);
  if (p.w < 0.5f) return;
  int material = objects[int(p.w) - 1].info.x;
  if (material < 0) return;
  vec3 n = normalize(texelFetch(light_normal, ivec3(texel, layer), 0).xyz);
  ViewGPU view = frame.light_views[layer];
  vec3 power;
  float cos_i;
  if (int(light.position.w) == LUCENT_LIGHT_DIRECTIONAL) {
    cos_i = dot(n, -light.position.xyz);
    // The texel's footprint on the view plane, perpendicular to the light: flux = E_perp A_texel.
    float texel_width = view.direction.w / float(size);
    power = light.power.rgb * texel_width * texel_width;
  } else {
    vec3 w_l;
    vec3 irradiance = light_incidence(light, p.xyz, w_l);  // I cone / d^2
    cos_i = dot(n, w_l);
    vec3 to_x = p.xyz - light.position.xyz;
    float d2 = max(dot(to_x, to_x), 1e-12f);
    // Solid angle of a texel of a perspective (frustum or cube-face) view of S x S texels and half-angle a:
    //   d_omega = (2 tan(a) / S)^2 cos^3(phi),
    // phi the angle between the direction to the texel and the view's axis (the texel's area on the image plane
    // at unit distance, (2 tan(a) / S)^2, seen at distance 1 / cos(phi) and tilted by phi). ViewGPU.radiance.w
    // holds the texel angle 2a / S. The power reaching the texel's surface patch (area d^2 d_omega / cos_i) is
    // irradiance * cos_i * area = I cone d_omega.
    float half_angle = 0.5f * view.radiance.w * float(size);
    float plane_texel = 2.0f * tan(half_angle) / float(size);
    float cos_phi = dot(to_x * inversesqrt(d2), view.direction.xyz);
    if (cos_phi <= 0.0f) return;
    float d_omega = plane_texel * plane_texel * cos_phi * cos_phi * cos_phi;
    power = irradiance * d2 * d_omega;
  }
  if (cos_i <= 0.0f) return;
  int voxel = inside_voxel_near(p.xyz, n);
  if (voxel < 0) return;
  vec3 entering = fresnel_transmittance(materials[material].sigma_a.w, cos_i) * power;
  uvec3 units = uvec3(entering / u_flux_unit + 0.5f);
  for (int band = 0; band < 3; ++band)
    if (units[band] != 0u) atomicAdd(flux[3 * voxel + band], units[band]);
}
