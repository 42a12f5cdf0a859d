// ggx.h: specular reflection of a light off the smooth-ish dielectric boundary of a translucent object:
// GGX (Trowbridge-Reitz) microfacet distribution with the separable Smith masking term and the exact
// dielectric Fresnel reflectance. Walter et al., "Microfacet Models for Refraction through Rough Surfaces",
// EGSR 2007, eqs. 20, 33-34.
#ifndef LUCENT_BRDF_GGX_H
#define LUCENT_BRDF_GGX_H
#include "shared/bridge.h"
#include "bssrdf/constants.h"
#include "bssrdf/fresnel.h"

LUCENT_SHADER_BEGIN

LUCENT_INLINE float ggx_D(float cos_h, float alpha) {
  float a2 = alpha * alpha;
  float d = cos_h * cos_h * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

LUCENT_INLINE float ggx_G1(float cos_v, float alpha) {
  float a2 = alpha * alpha;
  return 2.0f * cos_v / (cos_v + sqrt(a2 + (1.0f - a2) * cos_v * cos_v));
}

// BRDF value f_r [1/sr] for unit n, toward-light w_l and toward-viewer w_o.
LUCENT_INLINE float ggx_dielectric_brdf(vec3 n, vec3 w_l, vec3 w_o, float alpha, float eta) {
  float cos_l = dot(n, w_l), cos_o = dot(n, w_o);
  if (cos_l <= 0.0f || cos_o <= 0.0f) return 0.0f;
  vec3 h = normalize(w_l + w_o);
  float F = fresnel_reflectance(eta, dot(h, w_o));
  return F * ggx_D(dot(n, h), alpha) * ggx_G1(cos_l, alpha) * ggx_G1(cos_o, alpha) / (4.0f * cos_l * cos_o);
}

LUCENT_SHADER_END

#endif
