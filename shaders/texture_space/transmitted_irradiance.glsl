// transmitted_irradiance.glsl: F_t E at a surface point, the irradiance that enters the medium: the sum over the
// frame's lights of E cos F_t(eta, cos) times the shadow-map visibility (light G-buffer). What E' holds per unit
// surface area (irradiance.comp) and what the hybrid method's local pattern gathers. Include after
// common/frame.glsl, common/lights.glsl and bssrdf/fresnel.h.
vec3 transmitted_irradiance(vec3 x, vec3 n, float eta) {
  vec3 E = vec3(0.0f);
  // loop bound: LUCENT_MAX_LIGHTS x 7 x 7; at most LUCENT_MAX_LIGHTS lights, each with at most 7 x 7 shadow taps
  for (int l = 0; l < frame.light_counts.x; ++l) {
    vec3 w_l;
    vec3 E_l = light_incidence(frame.lights[l], x, w_l);
    float cos_l = dot(n, w_l);
    if (cos_l <= 0.0f) continue;
    E += E_l * cos_l * fresnel_transmittance(eta, cos_l) * light_visibility(l, x, n);
  }
  return E;
}
