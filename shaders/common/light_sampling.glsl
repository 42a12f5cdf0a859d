// light_sampling.glsl: the Monte Carlo estimator of Dal Corso et al.'s eq. 9 for the scattered radiosity B(x_o)
// of one colour band from one light, with N samples drawn from p_exp (eqs. 10-12) and x_i, n_i looked up in the
// light's G-buffer. Shared by the radiosity-maps integration (per map texel) and the per-pixel baseline.
//
// Directional lights: samples are uniform over the light's orthographic view plane, where dA_plane =
// cos(theta_i) dA_i, so eq. 7's cos(theta_l) cancels against the Jacobian (eq. 9's extra cosine is not applied;
// see docs/methods/radiosity-maps.md). Point and spot lights: samples lie in the plane through x_o
// perpendicular to the light and are mapped to directions by the stereographic correction (eqs. 13-14); dividing
// by dA_plane / d omega cancels the irradiance's cos(theta_i) / d^2 in the same way (lights/point_light.h).
// Scenes without point or spot lights compile with LUCENT_DIRECTIONAL_LIGHTS_ONLY: llvmpipe executes both sides
// of a branch under a lane mask, and the unused point-light side cost the directional integration 1.7x.
#include "bssrdf/model.h"
#include "media/material_map.h"
#include "geometry/thickness_field.h"
#include "shared/random.h"

// Light l's sampling plane around x_o: directional, the light's view plane (uv_o: x_o's coordinates in it);
// point and spot, the plane through x_o perpendicular to the light (t1, t2 span it).
struct LightPlane {
  vec2 uv_o;
  vec3 axis, t1, t2;
};

LightPlane light_plane(int l, vec3 x_o) {
  LightGPU light = frame.lights[l];
  bool directional = int(light.position.w) == LUCENT_LIGHT_DIRECTIONAL;
  LightPlane p;
  p.uv_o = directional ? view_coords(frame.light_views[light.views.x], x_o).xy : vec2(0.0f);
  p.axis = directional ? -light.position.xyz : normalize(light.position.xyz - x_o);
  p.t1 = normalize(abs(p.axis.x) > 0.9f ? cross(p.axis, vec3(0.0f, 1.0f, 0.0f)) : cross(p.axis, vec3(1.0f, 0.0f, 0.0f)));
  p.t2 = cross(p.axis, p.t1);
  return p;
}

// The surface point light l's G-buffer shows at (r cos alpha, r sin alpha) from x_o in its sampling plane: false
// unless it is directly lit surface of `object`; else x_i, n_i, w_i (toward the light), cos_i = n_i . w_i > 0, and
// `weight` (an area in the plane) turned into the measure in which F_t S_d weight, times the light's power (per
// unit intensity for point lights), integrates E F_t S_d over the lit surface (the top of this file).
bool light_plane_entry(int l, LightPlane p, int object, vec3 x_o, float r, float alpha, out vec3 x_i, out vec3 n_i,
                       out vec3 w_i, out float cos_i, inout float weight) {
  LightGPU light = frame.lights[l];
  bool directional = int(light.position.w) == LUCENT_LIGHT_DIRECTIONAL;
  int layer;
  vec2 uv;
  x_i = x_o, n_i = p.axis, w_i = p.axis, cos_i = 0.0f;
  if (directional) {
    layer = light.views.x;
    uv = p.uv_o + r * vec2(cos(alpha), sin(alpha)) / frame.light_views[layer].direction.w;
    if (any(lessThan(uv, vec2(0.0f))) || any(greaterThanEqual(uv, vec2(1.0f)))) return false;
  } else {
#if defined(LUCENT_DIRECTIONAL_LIGHTS_ONLY)
    return false;
#else
    vec3 x_j = x_o + r * (cos(alpha) * p.t1 + sin(alpha) * p.t2);
    StereographicSample s = stereographic_sample(light.position.xyz, x_o, x_j);
    if (!point_light_lookup(light, light.views.x, light.views.y, s.direction, layer, uv)) return false;
    weight /= s.plane_area_per_solid_angle;
    if (int(light.position.w) == LUCENT_LIGHT_SPOT)
      weight *= spot_falloff(dot(s.direction, light.axis.xyz), light.power.w, light.axis.w);
#endif
  }
  // Look up x_i, n_i; only this object's directly lit surface contributes.
  ivec3 texel = ivec3(ivec2(uv * float(frame.light_counts.z)), layer);
  vec4 p_i = texelFetch(light_position, texel, 0);
  if (int(p_i.w) - 1 != object) return false;
  x_i = p_i.xyz;
  if (!directional) w_i = normalize(light.position.xyz - p_i.xyz);
  n_i = texelFetch(light_normal, texel, 0).xyz;
  cos_i = dot(n_i, w_i);
  return cos_i > 0.0f;
}

// B for one band from light l, without the factor pi * power[band] (and, for point lights, per unit intensity).
float band_radiosity(int band, int l, int object, MaterialGPU material, vec3 x_o, vec3 n_o, uint state, int samples) {
  float eta = material.sigma_a.w;
  int model = int(material.sigma_s.w);
  BandMedium m = bssrdf_band_medium(model, material.sigma_a[band], material.sigma_s[band], material.g[band], eta,
                                    material.g.w);
  LightPlane plane = light_plane(l, x_o);
  float sum = 0.0f;
  // loop bound: checked; N samples x 3 bands x the lights per invocation, refused on llvmpipe above the cap by per-pixel and radiosity-maps (platform::check_loop_iterations)
  for (int j = 0; j < samples; ++j) {
    // Sample (r, alpha) from p_exp (eq. 12) around x_o.
    float xi_1 = next_float(state + uint(2 * j));
    float xi_2 = next_float(state + uint(2 * j + 1));
    float r = -log(xi_1) / m.sigma_tr;
    float alpha = kTwoPi * xi_2;
    // 1 / p_exp(r, alpha) in area measure: p = sigma_tr e^{-sigma_tr r} / (2 pi r), with e^{-sigma_tr r} = xi_1.
    float weight = kTwoPi * r / (m.sigma_tr * xi_1);
    vec3 x_i, n_i, w_i;
    float cos_i;
    if (!light_plane_entry(l, plane, object, x_o, r, alpha, x_i, n_i, w_i, cos_i, weight)) continue;
    float S_d = bssrdf_Sd(model, m, eta, x_i, w_i, n_i, x_o, n_o);
    sum += S_d * fresnel_transmittance(eta, cos_i) * weight;
  }
  return sum / float(samples);
}

// Scattered radiosity B(x_o) in all bands from all lights, with `samples` samples per band and light;
// `stream_base` separates independent estimates (map texels). A textured material's coefficients are those at
// x_o's texture coordinates uv_o, where the light leaves (as in the CPU references).
vec3 scattered_radiosity(int object, vec3 x_o, vec3 n_o, vec2 uv_o, uint point_index, uint stream_base, int samples) {
  MaterialGPU material = materials[objects[object].info.x];
#if defined(LUCENT_MATERIAL_MAPS)
  material = material_at(material, uv_o);
#endif
  material.g.w = surface_thickness(objects[object].info, material.g.w, x_o);  // the multipole model's, at x_o
  vec3 B = vec3(0.0f);
  // loop bound: checked; the lights x 3 bands x N samples inside, refused on llvmpipe above the cap (platform::check_loop_iterations)
  for (int l = 0; l < frame.light_counts.x; ++l) {
    for (int band = 0; band < 3; ++band) {
      uint stream = uint((int(stream_base) * LUCENT_MAX_LIGHTS + l) * 3 + band);
      uint state = seed_from(frame.seeds.x, point_index, stream, frame.seeds.y);
      B[band] += kPi * frame.lights[l].power[band] * band_radiosity(band, l, object, material, x_o, n_o, state, samples);
    }
  }
  return B;
}
