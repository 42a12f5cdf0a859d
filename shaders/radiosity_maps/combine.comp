// combine.comp: step 3 of Dal Corso et al. 2015: per camera pixel, Algorithm 1 (K map look-ups weighted by
// multi-sampled visibility from each map's depth with eps_bias, positions offset by eps_comb), then the
// outgoing radiance of eq. 5, L_o = F_t(w_o) B / pi, plus optional GGX specular reflection of the lights.
// Opaque objects get Lambertian direct light with shadows from the light G-buffer, plus the emergent light of
// the translucent objects gathered from virtual point lights (Section 3.4, eq. 15).
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "radiosity_maps/map_lookup.glsl"
#include "common/direct_shading.glsl"
#include "radiosity_maps/vpl_gather.glsl"
#include "bssrdf/fresnel.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(binding = LUCENT_TEX_CAMERA_POSITION) uniform sampler2D camera_position;
layout(binding = LUCENT_TEX_CAMERA_NORMAL) uniform sampler2D camera_normal;
layout(rgba32f, binding = LUCENT_IMAGE_HDR) uniform writeonly image2D hdr;
layout(std430, binding = LUCENT_BINDING_COUNTERS) buffer CounterBlock { CountersGPU counters; };

vec3 shade_translucent(vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  float eta = material.sigma_a.w;
  vec4 B = combine_maps(x, n);
  atomicAdd(counters.translucent_pixels, 1u);
  if (B.w > 0.0f) atomicAdd(counters.covered_pixels, 1u);
  if (int(frame.options.y) == LUCENT_VIEW_COVERAGE) return B.w > 0.0f ? vec3(0.2f) : vec3(1.0f, 0.0f, 1.0f);
  return fresnel_transmittance(eta, dot(n, w_o)) * kInvPi * B.rgb + specular_direct(x, n, w_o, eta) + environment_specular(n, w_o, eta);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.sizes.z || pixel.y >= frame.sizes.w) return;
  vec4 p = texelFetch(camera_position, pixel, 0);
  if (p.w < 0.5f) {
    imageStore(hdr, pixel, vec4(miss_radiance(pixel), 0.0f));
    return;
  }
  ObjectGPU object = objects[int(p.w) - 1];
  vec3 n = normalize(texelFetch(camera_normal, pixel, 0).xyz);
  vec3 w_o = normalize(frame.camera_position.xyz - p.xyz);
  vec3 L;
  if (object.info.x < 0) {
    if (dot(n, w_o) < 0.0f) n = -n;  // two-sided opaque surfaces (planes seen from below)
    L = lambertian_direct(p.xyz, n, object.albedo.rgb) + object.albedo.rgb * kInvPi * vpl_irradiance(p.xyz, n);
  } else {
    L = shade_translucent(p.xyz, n, w_o, materials[object.info.x]);
  }
  imageStore(hdr, pixel, vec4(L, 1.0f));
}
