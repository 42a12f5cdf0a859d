// diffuse_lighting.glsl: the irradiance that enters a translucent surface point from every light, for the diffuse
// baselines (diffuse-wrap, screen-space). Includes common/frame.glsl and common/lights.glsl first.
//
// Per light, with c = n . w_l: the wrapped cosine c_w = max(0, (c + w) / (1 + w)) (wrap lighting, w in [0, 1]; w = 0
// is Lambert's cosine), the light's irradiance E on a surface facing it, and the Fresnel transmittance of the boundary
// F_t(eta, c_w), evaluated at the wrapped cosine so that the wrapped light is not cut off at c = 0:
//
//   E_t = sum_l F_t(eta, c_w) c_w E_l V_l
//
// V_l the light's shadow test (light G-buffer) where c > 0; where c <= 0 only wrapped light arrives, and the shadow
// map cannot tell the point's own surface from an occluder, so it is not tested there. Environment lights
// (directional lights standing in for the map) are lights like the others.
#include "bssrdf/fresnel.h"

vec3 transmitted_irradiance(vec3 x, vec3 n, float eta, float wrap, bool shadows) {
  vec3 E_t = vec3(0.0f);
  // loop bound: LUCENT_MAX_LIGHTS x 7 x 7; the light G-buffer holds at most LUCENT_MAX_LIGHTS lights, each tested with at most 7 x 7 shadow taps (visibility_taps <= 7)
  for (int l = 0; l < frame.light_counts.x; ++l) {
    vec3 w_l;
    vec3 E = light_incidence(frame.lights[l], x, w_l);
    float c = dot(n, w_l);
    float c_w = max(0.0f, (c + wrap) / (1.0f + wrap));
    if (c_w <= 0.0f) continue;
    float V = shadows && c > 0.0f ? light_visibility(l, x, n) : 1.0f;
    E_t += fresnel_transmittance(eta, c_w) * c_w * E * V;
  }
  return E_t;
}
