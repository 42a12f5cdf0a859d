// combine.comp: step 3 of Dal Corso et al. 2015: per camera pixel, Algorithm 1 (K map look-ups weighted by
// multi-sampled visibility from each map's depth with eps_bias, positions offset by eps_comb), then the
// outgoing radiance of eq. 5, L_o = F_t(w_o) B / pi. Opaque objects also receive the emergent light of the
// translucent objects gathered from virtual point lights (Section 3.4, eq. 15). The rest of the pixel's shading
// (misses, opaque direct light, specular) is the shared skeleton of common/camera_pixel.glsl.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "methods/radiosity_maps/shaders/method_block.glsl"
#include "methods/radiosity_maps/shaders/map_lookup.glsl"
#include "methods/radiosity_maps/shaders/vpl_gather.glsl"
#define LUCENT_OPAQUE_INDIRECT(x, n) vpl_irradiance(x, n)
#include "common/camera_pixel.glsl"

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  vec4 B = combine_maps(x, n);
  if (method.counts.w == LUCENT_VIEW_COVERAGE) return vec4(B.w > 0.0f ? vec3(0.2f) : vec3(1.0f, 0.0f, 1.0f), B.w);
  return vec4(fresnel_transmittance(material.sigma_a.w, dot(n, w_o)) * kInvPi * B.rgb, B.w);
}
