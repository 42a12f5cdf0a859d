// direct_shading.glsl: direct light from every light with shadows: Lambertian opaque surfaces, and the GGX
// specular reflection on a translucent object's dielectric boundary. Shared by the methods' final passes.
#include "brdf/ggx.h"
#include "bssrdf/constants.h"
#include "bssrdf/fresnel.h"
#include "common/environment.glsl"

vec3 lambertian_direct(vec3 x, vec3 n, vec3 albedo) {
  vec3 L = vec3(0.0f);
  // loop bound: LUCENT_MAX_LIGHTS x 7 x 7; at most LUCENT_MAX_LIGHTS lights, each with at most 7 x 7 shadow taps
  for (int l = 0; l < frame.light_counts.x; ++l) {
    vec3 w_l;
    vec3 E = light_incidence(frame.lights[l], x, w_l);
    float cos_l = dot(n, w_l);
    if (cos_l <= 0.0f) continue;
    L += albedo * kInvPi * E * cos_l * light_visibility(l, x, n);
  }
  return L;
}

// Zero unless the specular term is on (frame.shading.x); roughness frame.shading.y. Lights standing in for an
// environment map have no highlight: environment_specular() reflects the map itself.
vec3 specular_direct(vec3 x, vec3 n, vec3 w_o, float eta) {
  vec3 L = vec3(0.0f);
  if (frame.shading.x <= 0.5f) return L;
  // loop bound: LUCENT_MAX_LIGHTS x 7 x 7; at most LUCENT_MAX_LIGHTS lights, each with at most 7 x 7 shadow taps
  for (int l = 0; l < frame.light_counts.x; ++l) {
    LightGPU light = frame.lights[l];
    if (int(light.position.w) == LUCENT_LIGHT_DIRECTIONAL && light.axis.w < 0.5f) continue;  // environment light
    vec3 w_l;
    vec3 E = light_incidence(light, x, w_l);
    float f_r = ggx_dielectric_brdf(n, w_l, w_o, frame.shading.y, eta);
    L += f_r * max(dot(n, w_l), 0.0f) * E * light_visibility(l, x, n);
  }
  return L;
}

// Specular reflection of the environment map (Dal Corso et al. 2015, Section 4): the map looked up in the
// reflected direction times the Fresnel reflectance; rougher surfaces read blurrier mip levels.
vec3 environment_specular(vec3 n, vec3 w_o, float eta) {
  if (frame.shading.x <= 0.5f || (frame.environment.x & LUCENT_ENVIRONMENT_MAP) == 0) return vec3(0.0f);
  float F_r = 1.0f - fresnel_transmittance(eta, max(dot(n, w_o), 0.0f));
  float lod = frame.shading.y * log2(float(textureSize(environment_map, 0).x));
  return F_r * environment_radiance(reflect(-w_o, n), lod);
}
