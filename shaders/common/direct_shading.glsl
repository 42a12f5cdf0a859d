// direct_shading.glsl: direct light from every light with shadows: Lambertian opaque surfaces, and the GGX
// specular reflection on a translucent object's dielectric boundary. Shared by the methods' final passes.
#include "brdf/ggx.h"
#include "bssrdf/constants.h"

vec3 lambertian_direct(vec3 x, vec3 n, vec3 albedo) {
  vec3 L = vec3(0.0f);
  for (int l = 0; l < frame.counts.x; ++l) {
    vec3 w_l;
    vec3 E = light_incidence(frame.lights[l], x, w_l);
    float cos_l = dot(n, w_l);
    if (cos_l <= 0.0f) continue;
    L += albedo * kInvPi * E * cos_l * light_visibility(l, x, n);
  }
  return L;
}

// Zero unless the specular term is on (frame.options.z); roughness frame.biases.w.
vec3 specular_direct(vec3 x, vec3 n, vec3 w_o, float eta) {
  vec3 L = vec3(0.0f);
  if (frame.options.z <= 0.5f) return L;
  for (int l = 0; l < frame.counts.x; ++l) {
    vec3 w_l;
    vec3 E = light_incidence(frame.lights[l], x, w_l);
    float f_r = ggx_dielectric_brdf(n, w_l, w_o, frame.biases.w, eta);
    L += f_r * max(dot(n, w_l), 0.0f) * E * light_visibility(l, x, n);
  }
  return L;
}
