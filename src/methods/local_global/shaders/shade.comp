// shade.comp: the combination (Lensch et al. 2002, Sections 6.4 and 3, Eq. 1): per camera pixel on a translucent
// object, L = F_t(eta, n . w_o) / pi (B_l + B^d + B^g'): B_l read from the local response at the pixel's atlas
// coordinates (bilinear over the four nearest texels with a covered centre on the same object), B^d + B^g'
// interpolated over the pixel's triangle by the atlas_view pass.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/fresnel.h"
#include "methods/local_global/local_global_io.h"
#include "common/camera_pixel.glsl"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LocalGlobalGPU method; };
layout(binding = LUCENT_TEX_LG_TEXEL_INDEX) uniform isampler2D texel_index;
layout(binding = LUCENT_TEX_LG_LOCAL) uniform sampler2D local_radiosity;
layout(binding = LUCENT_TEX_LG_VIEW_ATLAS) uniform sampler2D view_atlas;
layout(binding = LUCENT_TEX_LG_VIEW_RADIOSITY) uniform sampler2D view_radiosity;
layout(binding = LG_TEX_POSITION) uniform sampler2D texel_position;

// B_l at atlas coordinates uv on object `object_index`; a = 0 when no texel of the object is near.
vec4 local_at(vec2 uv, int object_index) {
  int size = method.counts.x;
  vec2 t = uv * float(size) - 0.5f;
  ivec2 base = ivec2(floor(t));
  vec2 f = t - vec2(base);
  vec4 sum = vec4(0.0f);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      ivec2 q = clamp(base + ivec2(i, j), ivec2(0), ivec2(size - 1));
      if (texelFetch(texel_index, q, 0).r < 0) continue;
      if (int(texelFetch(texel_position, q, 0).w) - 1 != object_index) continue;
      float w = (i == 0 ? 1.0f - f.x : f.x) * (j == 0 ? 1.0f - f.y : f.y) + 1e-6f;
      sum += vec4(w * texelFetch(local_radiosity, q, 0).rgb, w);
    }
  if (sum.a > 0.0f) return vec4(sum.rgb / sum.a, 1.0f);
  // Chart borders: the nearest covered texel of the object within two texels.
  ivec2 c = ivec2(floor(uv * float(size)));
  float best = 1e30f;
  vec4 result = vec4(0.0f);
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      ivec2 q = c + ivec2(dx, dy);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(size)))) continue;
      if (texelFetch(texel_index, q, 0).r < 0) continue;
      if (int(texelFetch(texel_position, q, 0).w) - 1 != object_index) continue;
      float d = float(dx * dx + dy * dy);
      if (d < best) {
        best = d;
        result = vec4(texelFetch(local_radiosity, q, 0).rgb, 1.0f);
      }
    }
  return result;
}

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  vec4 view = texelFetch(view_atlas, pixel, 0);
  if (int(view.z + 0.5f) - 1 != object_index) return vec4(0.0f);
  vec3 B = texelFetch(view_radiosity, pixel, 0).rgb;
  vec4 local = local_at(view.xy, object_index);
  if (method.options.x == LUCENT_LG_SHOW_LOCAL) B = local.rgb;
  else if (method.options.x != LUCENT_LG_SHOW_GLOBAL) B += local.rgb;
  float eta = material.sigma_a.w;
  return vec4(fresnel_transmittance(eta, dot(n, w_o)) * kInvPi * max(B, vec3(0.0f)), 1.0f);
}
