// shade.comp: stage 3 of texture-space importance sampling (Chang et al. 2008, Eq. 11): for every camera pixel on
// a translucent object, L = F_t(eta, n . w_o) sum_i weight_i S_d(x_i, w_l, n_i; x_o, n_o) over the frame's samples on
// the same object (weight_i = E'(x_i) E'_total / (E'(x_i) N) per band, texture_space/irradiance_sample.comp). Eq. 11
// sums the radially symmetric R_d(|x_o - x_i|) / pi, which puts x_o in x_i's tangent plane with n_o = n_i and the
// light at normal incidence; the sampling density holds only E', so the model's full S_d with each sample's own
// position and normal (texture G-buffer) and the light's direction is summed with the same weights
// (texture_space/transmitted_sd.glsl). View dependent: accumulates only while nothing, camera included, changes.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/model.h"
#include "media/material_map.h"
#include "geometry/thickness_field.h"
#include "methods/texture_space_is/texture_space_is_io.h"
#include "texture_space/transmitted_sd.glsl"
#include "common/camera_pixel.glsl"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { TextureSpaceIsGPU method; };
layout(binding = TSIS_TEX_POSITION) uniform sampler2D texel_position;
layout(binding = TSIS_TEX_NORMAL_RATIO) uniform sampler2D texel_normal_ratio;
layout(std430, binding = LUCENT_BINDING_TSIS_SAMPLES) readonly buffer Samples {
  vec4 total;
  TsisSampleGPU samples[];
};
layout(rgba32f, binding = LUCENT_IMAGE_TSIS_SUM) uniform image2D accumulated;  // rgb: sum of L / F_t, a: frames

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
#if defined(LUCENT_MATERIAL_MAPS)
  material = material_at(material, camera_uv(pixel));  // S_d with the exit point's coefficients
#endif
  float eta = material.sigma_a.w;
  int model = int(material.sigma_s.w);
  float thickness = surface_thickness(objects[object_index].info, material.g.w, x);
  BandMedium m[3];
  for (int band = 0; band < 3; ++band)
    m[band] = bssrdf_band_medium(model, material.sigma_a[band], material.sigma_s[band], material.g[band], eta, thickness);
  vec3 B = vec3(0.0f);
  int N = min(method.counts.x, LUCENT_TSIS_MAX_SAMPLES);
  // loop bound: checked; texture_space_is.cpp counts N x (this loop, transmitted_Sd's light and band loops, photon
  // beam's integral) and refuses on llvmpipe a setting past the loop budget
  for (int i = 0; i < N; ++i) {
    TsisSampleGPU s = samples[i];
    vec4 p = texelFetch(texel_position, s.texel.xy, 0);
    if (int(p.w) - 1 != object_index) continue;
    vec3 n_i = normalize(texelFetch(texel_normal_ratio, s.texel.xy, 0).xyz);
    B += s.weight.rgb * transmitted_Sd(model, m, eta, p.xyz, n_i, x, n);
  }
  vec4 sum = frame.seeds.z != 0u ? vec4(0.0f) : imageLoad(accumulated, pixel);
  sum += vec4(B, 1.0f);
  imageStore(accumulated, pixel, sum);
  return vec4(fresnel_transmittance(eta, dot(n, w_o)) * sum.rgb / sum.a, 1.0f);
}
