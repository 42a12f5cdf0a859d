// transmitted_sd.glsl: the model's full S_d seen by a texture-space sample: the S_d that multiplies the transmitted
// irradiance F_t E stored in E' (irradiance.comp), for the texture-space methods' shade passes. Include after
// common/frame.glsl, common/lights.glsl and bssrdf/model.h.

// The model's full S_d(x_i, w_l, n_i; x_o, n_o) per band, averaged over the frame's lights with the weights
// F_t E_l cos_l (shadowed) that make up the transmitted irradiance at x_i: sum_l F_t E_l S_d(w_l) / sum_l F_t E_l.
// A sample drawn from E' (which holds F_t E times the area, and no direction) times this S_d is the reference's
// integrand E_l T12 cos S_d summed over the lights, with no Fresnel or cosine counted twice. w_l is the direction
// toward light l (the directional dipole's incident-direction argument, refracted inside the model). With one light
// the average is that light's S_d and its visibility need not be looked up (E' > 0 already says it is lit).
// `medium` are the three bands at x_o (the coefficients where the light leaves, as the references).
vec3 transmitted_Sd(int model, BandMedium medium[3], float eta, vec3 x_i, vec3 n_i, vec3 x_o, vec3 n_o) {
  vec3 weighted = vec3(0.0f), E = vec3(0.0f);
  // loop bound: checked; texture-space-is and hybrid count it per sample, with its shadow taps and bands
  for (int l = 0; l < frame.light_counts.x; ++l) {
    vec3 w_l;
    vec3 E_l = light_incidence(frame.lights[l], x_i, w_l);
    float cos_l = dot(n_i, w_l);
    if (cos_l <= 0.0f) continue;
    if (frame.light_counts.x == 1)
      return vec3(bssrdf_Sd(model, medium[0], eta, x_i, w_l, n_i, x_o, n_o),
                  bssrdf_Sd(model, medium[1], eta, x_i, w_l, n_i, x_o, n_o),
                  bssrdf_Sd(model, medium[2], eta, x_i, w_l, n_i, x_o, n_o));
    vec3 e = E_l * cos_l * fresnel_transmittance(eta, cos_l) * light_visibility(l, x_i, n_i);
    E += e;
    for (int band = 0; band < 3; ++band)
      weighted[band] += e[band] * bssrdf_Sd(model, medium[band], eta, x_i, w_l, n_i, x_o, n_o);
  }
  vec3 S_d = vec3(0.0f);
  for (int band = 0; band < 3; ++band)
    if (E[band] > 0.0f) S_d[band] = weighted[band] / E[band];
  return S_d;
}
