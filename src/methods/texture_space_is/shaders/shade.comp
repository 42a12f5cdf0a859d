// shade.comp: stage 3 of texture-space importance sampling (Chang et al. 2008, Eq. 11): for every camera pixel on
// a translucent object, L = F_t(eta, n . w_o) / pi sum_i weight_i R_d(|x_o - x_i|) over the frame's samples on
// the same object (weight_i = E'(x_i) E'_total / (E'(x_i) N) per band, texture_space/irradiance_sample.comp), with the model's radially
// symmetric R_d (bssrdf/model.h). View dependent: accumulates only while nothing, camera included, changes.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/model.h"
#include "media/material_map.h"
#include "methods/texture_space_is/texture_space_is_io.h"
#include "common/camera_pixel.glsl"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { TextureSpaceIsGPU method; };
layout(binding = TSIS_TEX_POSITION) uniform sampler2D texel_position;
layout(std430, binding = LUCENT_BINDING_TSIS_SAMPLES) readonly buffer Samples {
  vec4 total;
  TsisSampleGPU samples[];
};
layout(rgba32f, binding = LUCENT_IMAGE_TSIS_SUM) uniform image2D accumulated;  // rgb: sum of L / F_t, a: frames

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
#if defined(LUCENT_MATERIAL_MAPS)
  material = material_at(material, camera_uv(pixel));  // R_d with the exit point's coefficients
#endif
  float eta = material.sigma_a.w;
  int model = int(material.sigma_s.w);
  BandMedium m[3];
  for (int band = 0; band < 3; ++band)
    m[band] = make_band_medium(material.sigma_a[band], material.sigma_s[band], material.g[band]);
  vec3 B = vec3(0.0f);
  for (int i = 0; i < method.counts.x; ++i) {
    TsisSampleGPU s = samples[i];
    vec4 p = texelFetch(texel_position, s.texel.xy, 0);
    if (int(p.w) - 1 != object_index) continue;
    float r = length(x - p.xyz);
    for (int band = 0; band < 3; ++band) B[band] += s.weight[band] * bssrdf_radial_Rd(model, m[band], eta, r);
  }
  vec4 sum = frame.seeds.z != 0u ? vec4(0.0f) : imageLoad(accumulated, pixel);
  sum += vec4(B, 1.0f);
  imageStore(accumulated, pixel, sum);
  return vec4(fresnel_transmittance(eta, dot(n, w_o)) * kInvPi * sum.rgb / sum.a, 1.0f);
}
