// march.comp: subsurface texture mapping (Francois et al. 2006 as in Norberg 2010, Section 2.1.4): for every camera
// pixel on a translucent object, single scattering ray-marched along the refracted view ray from P to M_max,
// Depth_max below the surface, through a stack of up to four layers whose thicknesses are read from the layer maps
// at texture coordinates moved by the tangent-space projection of each sample's offset (Section 2.1.2):
//
//   L(P, w_o) = T(eta, n.w_o) / eta^2  sum_M  sigma_s(M) p(M) E_in(M) exp(-int_P^M sigma_t) delta_M
//
// attenuation along the view ray accumulated step by step (Eq. 8); E_in the light refracted into the approximating
// plane Pi_M (Eq. 10: the tangent plane at P blended into the least-squares plane toward M_max), F_t E cos_i /
// cos_t (the beam's compression), times the reduced intensity through the layers above M along the refracted light
// path |K'M| = h / cos_t (Eq. 11 with the refracted direction; Eqs. 12-14 with Eq. 13's averaged thicknesses). With
// `jitter` every sample moves by one random fraction of a step per pixel and frame, and the frames are averaged.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/fresnel.h"
#include "media/layer_stack.h"
#include "shared/random.h"
#include "methods/layered_stm/layered_stm_io.h"
#include "common/camera_pixel.glsl"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LayeredStmGPU method; };
layout(rgba32f, binding = LUCENT_IMAGE_LSTM_SUM) uniform image2D accumulated;  // rgb: sum of estimates, a: frames
layout(binding = LUCENT_TEX_LSTM_MAPS) uniform sampler2D layer_maps;
layout(binding = LUCENT_TEX_LSTM_SURFACE) uniform sampler2D surface;
layout(binding = LUCENT_TEX_LSTM_GRADIENT_U) uniform sampler2D gradient_u;
layout(binding = LUCENT_TEX_LSTM_GRADIENT_V) uniform sampler2D gradient_v;
layout(binding = LUCENT_TEX_LSTM_PLANE_NORMAL) uniform sampler2D plane_normal;
layout(binding = LUCENT_TEX_LSTM_PLANE_POINT) uniform sampler2D plane_point;

// Layer thicknesses [scene units] at texture coordinates uv (layers beyond the stack's count are 0 thick).
vec4 thickness_at(vec2 uv, vec4 mask) { return textureLod(layer_maps, uv, 0.0f) * method.stack.x * mask; }

vec3 march(vec3 x, vec3 n, vec3 w_o, vec2 uv, vec3 gu, vec3 gv, vec3 fit_n, vec3 fit_p, MaterialGPU material,
           uint seed) {
  float eta = material.sigma_a.w;
  float cos_o = dot(n, w_o);
  if (cos_o <= 0.0f) return vec3(0.0f);
  // One layer of the object's own material when the method defines none.
  int layers = method.counts.y;
  vec3 sigma_s[4], sigma_t[4], k[4];
  for (int i = 0; i < 4; ++i) {
    sigma_s[i] = method.sigma_s[i].rgb;
    sigma_t[i] = method.sigma_t[i].rgb;
    k[i] = method.k[i].rgb;
  }
  if (layers == 0) {
    layers = 1;
    sigma_s[0] = material.sigma_s.xyz;
    sigma_t[0] = material.sigma_a.xyz + material.sigma_s.xyz;
    k[0] = vec3(schlick_k_from_g(material.g.x), schlick_k_from_g(material.g.y), schlick_k_from_g(material.g.z));
  }
  vec4 mask = vec4(1.0f, layers > 1 ? 1.0f : 0.0f, layers > 2 ? 1.0f : 0.0f, layers > 3 ? 1.0f : 0.0f);

  // Lights at P: irradiance (shadowed at P) and direction toward each.
  vec3 E[LUCENT_MAX_LIGHTS];
  vec3 w_l[LUCENT_MAX_LIGHTS];
  bool any_light = false;
  // loop bound: LUCENT_MAX_LIGHTS x 7 x 7; at most LUCENT_MAX_LIGHTS lights, each with at most 7 x 7 shadow taps
  for (int l = 0; l < frame.light_counts.x; ++l) {
    E[l] = light_incidence(frame.lights[l], x, w_l[l]);
    if (any(greaterThan(E[l], vec3(0.0f)))) E[l] *= light_visibility(l, x, n);
    any_light = any_light || any(greaterThan(E[l], vec3(0.0f)));
  }
  if (!any_light) return vec3(0.0f);

  vec3 w_v = refract(-w_o, n, 1.0f / eta);  // the view ray inside, away from P
  float cos_v = max(-dot(w_v, n), 1e-4f);
  float depth = method.stack.x;
  float path = depth / cos_v;  // |P M_max|
  int samples = method.counts.x;
  float step_length = path / float(samples);
  float offset = method.counts.z != 0 ? next_float(seed) : 0.5f;

  vec3 radiance = vec3(0.0f);
  vec3 attenuation = vec3(1.0f);  // exp(-int_P^M sigma_t), Eq. 8
  float previous = 0.0f;
  // loop bound: param.samples x LUCENT_MAX_LIGHTS; the samples parameter's range, the light loop inside
  for (int i = 0; i < samples; ++i) {
    float s = (float(i) + offset) * step_length;
    vec3 M = x + s * w_v;
    vec2 uv_m = uv + vec2(dot(M - x, gu), dot(M - x, gv));
    vec4 thickness_m = thickness_at(uv_m, mask);
    int layer = stack_layer_at(thickness_m, s * cos_v);
    vec3 layer_sigma_t = layer < 4 ? sigma_t[layer] : vec3(0.0f);
    attenuation *= exp(-layer_sigma_t * (s - previous));
    previous = s;
    if (layer >= 4) continue;
    // Pi_M (Eq. 10): alpha = |M M_max|, beta = |M P|.
    float alpha = path - s, beta = s;
    vec3 n_m = normalize(alpha * n + beta * fit_n);
    vec3 p_m = (alpha * x + beta * fit_p) / (alpha + beta);
    float h = max(dot(p_m - M, n_m), 0.0f);
    // loop bound: param.samples x LUCENT_MAX_LIGHTS; at most LUCENT_MAX_LIGHTS lights per march sample
    for (int l = 0; l < frame.light_counts.x; ++l) {
      float cos_i = dot(w_l[l], n_m);
      if (cos_i <= 0.0f || all(equal(E[l], vec3(0.0f)))) continue;
      vec3 w_t = refract(-w_l[l], n_m, 1.0f / eta);  // the light's direction of travel inside
      float cos_t = max(-dot(w_t, n_m), 1e-4f);
      float km = h / cos_t;  // |K'M|, Eq. 11
      vec3 K = M - km * w_t;
      vec2 uv_k = uv + vec2(dot(K - x, gu), dot(K - x, gv));
      vec4 D = 0.5f * (thickness_m + thickness_at(uv_k, mask));  // Eq. 13
      vec3 reduced = stack_light_transmittance(km, D, cos_t, sigma_t[0], sigma_t[1], sigma_t[2], sigma_t[3]);
      vec3 E_in = E[l] * fresnel_transmittance(eta, cos_i) * cos_i / cos_t;
      float cos_scatter = dot(w_t, -w_v);
      vec3 phase = vec3(schlick_phase(k[layer].r, cos_scatter), schlick_phase(k[layer].g, cos_scatter),
                        schlick_phase(k[layer].b, cos_scatter));
      radiance += sigma_s[layer] * phase * E_in * reduced * attenuation * step_length;
    }
  }
  return fresnel_transmittance(eta, cos_o) / (eta * eta) * radiance;
}

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  vec4 s = texelFetch(surface, pixel, 0);
  if (s.w < 0.5f || int(s.z + 0.5f) != object_index + 1) return vec4(0.0f);
  float tiling = method.stack.y;
  vec3 gu = tiling * texelFetch(gradient_u, pixel, 0).xyz, gv = tiling * texelFetch(gradient_v, pixel, 0).xyz;
  vec3 fit_n = texelFetch(plane_normal, pixel, 0).xyz;
  vec3 fit_p = texelFetch(plane_point, pixel, 0).xyz;
  if (!(dot(fit_n, fit_n) > 0.0f)) fit_n = n, fit_p = x;  // no plane fitted: the tangent plane throughout
  fit_n = normalize(fit_n);
  uint point = uint(pixel.y * frame.output_size.x + pixel.x);
  uint seed = seed_from(frame.seeds.x, point, frame.seeds.y, 0x5354u);
  vec3 estimate = march(x, n, w_o, tiling * s.xy, gu, gv, fit_n, fit_p, material, seed);
  vec4 sum = frame.seeds.z != 0u ? vec4(0.0f) : imageLoad(accumulated, pixel);
  sum += vec4(estimate, 1.0f);
  imageStore(accumulated, pixel, sum);
  return vec4(sum.rgb / sum.a, 1.0f);
}
