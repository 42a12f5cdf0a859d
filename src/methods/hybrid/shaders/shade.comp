// shade.comp: the hybrid of Chang et al. 2008, Section 4: per camera pixel on a translucent object,
// B = B_l + B_g, both integrals of the model's full S_d(x_i, w_l, n_i; x_o, n_o) over the lit surface, split by the
// distance |x_o - x_i| with W_l + W_g = 1 (bssrdf/hybrid_split.h). B_g (global): the frame's N texture-space samples
// (texture_space/irradiance_sample.comp) on the same object, pi sum_i weight_i S_d W_g (Eq. 11 with each sample's
// own position, normal and light direction, texture_space/transmitted_sd.glsl). B_l (local): as the paper's local
// part reads a light-space irradiance map, the circular pattern of L C + 1 points (the centre and L rings of C
// points, radii and stratum weights from bssrdf/hybrid_split.h) is laid around x_o in each light's sampling plane
// and each point looked up in the light's G-buffer (common/light_sampling.glsl), which shows only directly lit
// surface of the object; a stratum's weight, the integral of 2 pi r R_d W_l over it, is scaled per point by the
// ratio of the integrand there, pi S_d W_l F_t (in the plane's measure), to R_d W_l at the ring's radius, so a flat
// surface lit at normal incidence gets exactly the tabulated pattern (with a thickness grid, S_d at x_o's thickness
// over the R_d of the material's, which the pattern was built with). The pattern is turned by a random angle per
// pixel and frame. L = F_t(eta, n . w_o) / pi (B_l + B_g), accumulated while nothing, camera included, changes.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/model.h"
#include "bssrdf/hybrid_split.h"
#include "shared/random.h"
#include "methods/hybrid/hybrid_io.h"
#include "common/light_sampling.glsl"
#include "texture_space/transmitted_sd.glsl"
#include "common/camera_pixel.glsl"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { HybridGPU method; };
layout(binding = HYBRID_TEX_POSITION) uniform sampler2D texel_position;
layout(binding = HYBRID_TEX_NORMAL_RATIO) uniform sampler2D texel_normal_ratio;
layout(std430, binding = LUCENT_BINDING_HYBRID_SAMPLES) readonly buffer Samples {
  vec4 total;
  TsisSampleGPU samples[];
};
layout(std430, binding = LUCENT_BINDING_HYBRID_PATTERN) readonly buffer Pattern { vec4 pattern[]; };
layout(rgba32f, binding = LUCENT_IMAGE_HYBRID_SUM) uniform image2D accumulated;  // rgb: sum of B, a: frames

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  float eta = material.sigma_a.w;
  int model = int(material.sigma_s.w);
  int base = objects[object_index].info.x * method.counts.w;
  float Rp = pattern[base].x, K = method.split.x;
  float thickness = surface_thickness(objects[object_index].info, material.g.w, x);
  BandMedium m[3], m_pattern[3];  // at x_o's thickness; at the material's, which the local pattern was built with
  for (int band = 0; band < 3; ++band) {
    m[band] = bssrdf_band_medium(model, material.sigma_a[band], material.sigma_s[band], material.g[band], eta, thickness);
    m_pattern[band] = m[band];
    m_pattern[band].thickness = material.g.w;
  }
  // Global: the texture-space samples of S_d W_g.
  vec3 B = vec3(0.0f);
  int N = min(method.counts.x, LUCENT_HYBRID_MAX_SAMPLES);
  // loop bound: checked; hybrid.cpp counts the global samples, the local pattern per light and the loops inside
  // them (shade_loop_iterations) and refuses on llvmpipe a setting past the loop budget
  for (int i = 0; i < N; ++i) {
    TsisSampleGPU s = samples[i];
    vec4 p = texelFetch(texel_position, s.texel.xy, 0);
    if (int(p.w) - 1 != object_index) continue;
    vec3 n_i = normalize(texelFetch(texel_normal_ratio, s.texel.xy, 0).xyz);
    float w_g = hybrid_global_weight(length(x - p.xyz), Rp, K);
    B += kPi * w_g * s.weight.rgb * transmitted_Sd(model, m, eta, p.xyz, n_i, x, n);
  }
  // Local: the circular pattern of S_d W_l around x_o in each light's sampling plane.
  float turn = next_float(seed_from(frame.seeds.x, uint(pixel.x), uint(pixel.y), frame.seeds.y ^ 0x4b1du));
  int L = min(method.counts.y, LUCENT_HYBRID_MAX_RINGS), C = min(method.counts.z, LUCENT_HYBRID_MAX_RING_POINTS);
  // loop bound: checked; counted with the global samples (hybrid.cpp, shade_loop_iterations)
  for (int l = 0; l < frame.light_counts.x; ++l) {
    LightPlane plane = light_plane(l, x);
    vec3 B_l = vec3(0.0f);
    // loop bound: checked; counted with the global samples (hybrid.cpp, shade_loop_iterations)
    for (int j = 0; j <= L; ++j) {
      vec4 ring = pattern[base + 1 + j];
      int points = j == 0 ? 1 : C;
      vec3 sum = vec3(0.0f);
      // loop bound: checked; counted with the global samples (hybrid.cpp, shade_loop_iterations)
      for (int c = 0; c < points; ++c) {
        float phi = 2.0f * kPi * (float(c) + fract(turn + 0.618034f * float(j))) / float(points);
        vec3 x_i, n_i, w_i;
        float cos_i, weight = 1.0f;
        if (!light_plane_entry(l, plane, object_index, x, ring.w, phi, x_i, n_i, w_i, cos_i, weight)) continue;
        float f = weight * fresnel_transmittance(eta, cos_i) * hybrid_local_weight(length(x - x_i), Rp, K);
        for (int band = 0; band < 3; ++band) sum[band] += f * bssrdf_Sd(model, m[band], eta, x_i, w_i, n_i, x, n);
      }
      for (int band = 0; band < 3; ++band) {
        float profile = bssrdf_radial_Rd(model, m_pattern[band], eta, ring.w) * hybrid_local_weight(ring.w, Rp, K);
        if (profile > 0.0f) B_l[band] += ring[band] * kPi * sum[band] / (float(points) * profile);
      }
    }
    B += B_l * frame.lights[l].power.rgb;
  }
  vec4 acc = frame.seeds.z != 0u ? vec4(0.0f) : imageLoad(accumulated, pixel);
  acc += vec4(B, 1.0f);
  imageStore(accumulated, pixel, acc);
  return vec4(fresnel_transmittance(eta, dot(n, w_o)) * kInvPi * acc.rgb / acc.a, 1.0f);
}
