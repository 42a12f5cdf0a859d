// tonemap.h: exposure, tone-mapping operators and the sRGB transfer function, shared by the GPU tone-map
// pass and CPU image tools. Operators: linear (clamp), Reinhard x/(1+x), ACES filmic (Narkowicz 2015 fit).
#ifndef LUCENT_SHARED_TONEMAP_H
#define LUCENT_SHARED_TONEMAP_H
#include "shared/bridge.h"

#define LUCENT_TONEMAP_LINEAR 0
#define LUCENT_TONEMAP_REINHARD 1
#define LUCENT_TONEMAP_ACES 2

LUCENT_SHADER_BEGIN

LUCENT_INLINE float srgb_encode(float linear) {
  float c = clamp(linear, 0.0f, 1.0f);
  if (c <= 0.0031308f) return 12.92f * c;
  return 1.055f * pow(c, 1.0f / 2.4f) - 0.055f;
}

// The inverse: an sRGB-encoded value in [0, 1] -> linear (colour textures).
LUCENT_INLINE float srgb_decode(float encoded) {
  float c = clamp(encoded, 0.0f, 1.0f);
  if (c <= 0.04045f) return c / 12.92f;
  return pow((c + 0.055f) / 1.055f, 2.4f);
}

LUCENT_INLINE vec3 tonemap_operator(vec3 x, int op) {
  if (op == LUCENT_TONEMAP_REINHARD) return x / (vec3(1.0f) + x);
  if (op == LUCENT_TONEMAP_ACES) {
    vec3 num = x * (2.51f * x + vec3(0.03f));
    vec3 den = x * (2.43f * x + vec3(0.59f)) + vec3(0.14f);
    return clamp(num / den, vec3(0.0f), vec3(1.0f));
  }
  return clamp(x, vec3(0.0f), vec3(1.0f));
}

// Linear radiance -> display value in [0, 1] (sRGB encoded).
LUCENT_INLINE vec3 tonemap(vec3 radiance, float exposure_scale, int op) {
  vec3 mapped = tonemap_operator(max(radiance, vec3(0.0f)) * exposure_scale, op);
  return vec3(srgb_encode(mapped.x), srgb_encode(mapped.y), srgb_encode(mapped.z));
}

LUCENT_SHADER_END

#endif
