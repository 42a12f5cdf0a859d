// integrate.comp: step 2 of Dal Corso et al. 2015 (Fig. 3): the scattered radiosity B(x_o) of every texel of
// the K map views, by the Monte Carlo estimator of eq. 9 with N samples per colour band drawn from p_exp
// (eqs. 10-12) with that band's sigma_tr, x_i and n_i looked up in the directional lights' G-buffers.
//
// Change of variables: samples are uniform over the light's view plane, where dA_plane = cos(theta_i) dA_i, so
// the cos(theta_l) of eq. 7 cancels against the Jacobian; eq. 9's extra cos(theta_l) is not applied (see
// docs/methods/radiosity-maps.md). Each texel accumulates (sum of B over frames, number of frames).
#include "common/frame.glsl"
#include "bssrdf/model.h"
#include "shared/random.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(binding = LUCENT_TEX_MAP_POSITION) uniform sampler2DArray map_position;
layout(binding = LUCENT_TEX_MAP_NORMAL) uniform sampler2DArray map_normal;
layout(binding = LUCENT_TEX_LIGHT_POSITION) uniform sampler2DArray light_position;
layout(binding = LUCENT_TEX_LIGHT_NORMAL) uniform sampler2DArray light_normal;
layout(rgba32f, binding = LUCENT_IMAGE_RADIOSITY) uniform image2DArray radiosity;
layout(std430, binding = LUCENT_BINDING_COUNTERS) buffer CounterBlock { uint covered_texels; };

// Monte Carlo estimate of B for one band and one directional light (eq. 9, without the pi L factor).
float band_radiosity(int band, ViewGPU light, int light_layer, int object, MaterialGPU material, vec3 x_o, vec3 n_o,
                     uint state) {
  BandMedium m = make_band_medium(material.sigma_a[band], material.sigma_s[band], material.g[band]);
  float eta = material.sigma_a.w;
  int model = int(material.sigma_s.w);
  int light_size = frame.sizes.y;
  vec2 uv_o = view_texture_coords(light.clip_from_world, x_o).xy;
  vec3 w_i = -light.direction.xyz;
  float sum = 0.0f;
  for (int j = 0; j < frame.counts.z; ++j) {
    // Sample (r, alpha) from p_exp (eq. 12) around x_o in the light's view plane.
    float xi_1 = next_float(state + uint(2 * j));
    float xi_2 = next_float(state + uint(2 * j + 1));
    float r = -log(xi_1) / m.sigma_tr;
    float alpha = kTwoPi * xi_2;
    vec2 uv = uv_o + r * vec2(cos(alpha), sin(alpha)) / light.direction.w;
    if (any(lessThan(uv, vec2(0.0f))) || any(greaterThanEqual(uv, vec2(1.0f)))) continue;
    // Look up x_i, n_i; only this object's directly lit surface contributes.
    ivec3 texel = ivec3(ivec2(uv * float(light_size)), light_layer);
    vec4 p_i = texelFetch(light_position, texel, 0);
    if (int(p_i.w) - 1 != object) continue;
    vec3 n_i = texelFetch(light_normal, texel, 0).xyz;
    float cos_i = dot(n_i, w_i);
    if (cos_i <= 0.0f) continue;
    float S_d = bssrdf_Sd(model, m, eta, p_i.xyz, w_i, n_i, x_o, n_o);
    // Divide by p_exp(r, alpha) = sigma_tr e^{-sigma_tr r} / (2 pi), with e^{-sigma_tr r} = xi_1; times r (polar).
    sum += S_d * fresnel_transmittance(eta, cos_i) * kTwoPi * r / (m.sigma_tr * xi_1);
  }
  return sum / float(frame.counts.z);
}

void main() {
  ivec3 texel = ivec3(gl_GlobalInvocationID);
  int size = frame.sizes.x;
  if (texel.x >= size || texel.y >= size || texel.z >= frame.counts.y) return;
  vec4 previous = frame.seeds.z != 0u ? vec4(0.0f) : imageLoad(radiosity, texel);
  vec4 p_o = texelFetch(map_position, texel, 0);
  if (p_o.w < 0.5f) {
    imageStore(radiosity, texel, vec4(0.0f));
    return;
  }
  atomicAdd(covered_texels, 1u);
  int object = int(p_o.w) - 1;
  MaterialGPU material = materials[objects[object].info.x];
  vec3 n_o = normalize(texelFetch(map_normal, texel, 0).xyz);
  uint texel_index = uint(texel.y * size + texel.x);
  vec3 B = vec3(0.0f);
  for (int l = 0; l < frame.counts.x; ++l) {
    ViewGPU light = frame.lights[l];
    for (int band = 0; band < 3; ++band) {
      uint stream = uint(((texel.z * LUCENT_MAX_LIGHTS + l) * 3 + band));
      uint state = seed_from(frame.seeds.x, texel_index, stream, frame.seeds.y);
      B[band] += kPi * light.radiance[band] *
                 band_radiosity(band, light, l, object, material, p_o.xyz, n_o, state);
    }
  }
  imageStore(radiosity, texel, previous + vec4(B, 1.0f));
}
