// shade.comp: the hybrid of Chang et al. 2008, Section 4: per camera pixel on a translucent object,
// B = B_l + B_g. B_g (global): the frame's N texture-space samples (texture_space/irradiance_sample.comp) on the same
// object, sum_i weight_i R_d(r_i) W_g(r_i) (Eq. 11 with R_d W_g). B_l (local): the circular pattern of L C + 1
// points around x_o on its tangent plane (the centre and L rings of C points, radii and stratum weights from
// bssrdf/hybrid_split.h), each looked up in the camera neighbourhood (the camera G-buffer pixel the point projects
// to, if it lies on the same object within half the ring radius of the point) or else taken on the tangent plane,
// where the transmitted irradiance F_t E is evaluated; the pattern is turned by a random angle per pixel and frame.
// L = F_t(eta, n . w_o) / pi (B_l + B_g), accumulated while nothing, camera included, changes.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/model.h"
#include "bssrdf/hybrid_split.h"
#include "shared/random.h"
#include "methods/hybrid/hybrid_io.h"
#include "texture_space/transmitted_irradiance.glsl"
#include "common/camera_pixel.glsl"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { HybridGPU method; };
layout(binding = HYBRID_TEX_POSITION) uniform sampler2D texel_position;
layout(std430, binding = LUCENT_BINDING_HYBRID_SAMPLES) readonly buffer Samples {
  vec4 total;
  TsisSampleGPU samples[];
};
layout(std430, binding = LUCENT_BINDING_HYBRID_PATTERN) readonly buffer Pattern { vec4 pattern[]; };
layout(rgba32f, binding = LUCENT_IMAGE_HYBRID_SUM) uniform image2D accumulated;  // rgb: sum of B, a: frames

// F_t E at the surface point near q (on the tangent plane at distance r from x_o): the camera neighbourhood when
// the pixel q projects to shows the same object close to q, else q itself with x_o's normal.
vec3 local_irradiance(int object_index, vec3 q, vec3 n, float eta, float r) {
  vec4 clip = frame.clip_from_world * vec4(q, 1.0f);
  if (clip.w > 0.0f) {
    vec2 uv = clip.xy / clip.w * 0.5f + 0.5f;
    ivec2 px = ivec2(floor(uv * vec2(frame.output_size.xy)));
    if (all(greaterThanEqual(px, ivec2(0))) && all(lessThan(px, frame.output_size.xy))) {
      vec4 p = texelFetch(camera_position, px, 0);
      if (int(p.w) - 1 == object_index && distance(p.xyz, q) < 0.5f * r) {
        vec3 n_p = normalize(texelFetch(camera_normal, px, 0).xyz);
        return transmitted_irradiance(p.xyz, n_p, eta);
      }
    }
  }
  return transmitted_irradiance(q, n, eta);
}

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  float eta = material.sigma_a.w;
  int model = int(material.sigma_s.w);
  int base = objects[object_index].info.x * method.counts.w;
  float Rp = pattern[base].x, K = method.split.x;
  BandMedium m[3];
  for (int band = 0; band < 3; ++band)
    m[band] = make_band_medium(material.sigma_a[band], material.sigma_s[band], material.g[band]);
  // Global: the texture-space samples of R_d W_g.
  vec3 B = vec3(0.0f);
  for (int i = 0; i < method.counts.x; ++i) {
    TsisSampleGPU s = samples[i];
    vec4 p = texelFetch(texel_position, s.texel.xy, 0);
    if (int(p.w) - 1 != object_index) continue;
    float r = length(x - p.xyz);
    float w_g = hybrid_global_weight(r, Rp, K);
    for (int band = 0; band < 3; ++band) B[band] += s.weight[band] * w_g * bssrdf_radial_Rd(model, m[band], eta, r);
  }
  // Local: the circular pattern of R_d W_l around x_o.
  vec3 t = normalize(cross(n, abs(n.x) > 0.5f ? vec3(0.0f, 1.0f, 0.0f) : vec3(1.0f, 0.0f, 0.0f)));
  vec3 b = cross(n, t);
  float turn = next_float(seed_from(frame.seeds.x, uint(pixel.x), uint(pixel.y), frame.seeds.y ^ 0x4b1du));
  B += pattern[base + 1].xyz * transmitted_irradiance(x, n, eta);
  int L = method.counts.y, C = method.counts.z;
  for (int j = 1; j <= L; ++j) {
    vec4 ring = pattern[base + 1 + j];
    vec3 sum = vec3(0.0f);
    for (int c = 0; c < C; ++c) {
      float phi = 2.0f * kPi * (float(c) + fract(turn + 0.618034f * float(j))) / float(C);
      vec3 q = x + ring.w * (cos(phi) * t + sin(phi) * b);
      sum += local_irradiance(object_index, q, n, eta, ring.w);
    }
    B += ring.xyz * sum / float(C);
  }
  vec4 acc = frame.seeds.z != 0u ? vec4(0.0f) : imageLoad(accumulated, pixel);
  acc += vec4(B, 1.0f);
  imageStore(accumulated, pixel, acc);
  return vec4(fresnel_transmittance(eta, dot(n, w_o)) * kInvPi * acc.rgb / acc.a, 1.0f);
}
