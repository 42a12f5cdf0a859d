// environment.glsl: the environment map (lucent/environment.h; mapping in lights/equirect.h) as the shaders
// read it: radiance in a direction, and what camera rays that miss the scene see.
#include "lights/equirect.h"

layout(binding = LUCENT_TEX_ENVIRONMENT) uniform sampler2D environment_map;

vec3 environment_radiance(vec3 direction, float lod) {
  return textureLod(environment_map, equirect_uv(direction), lod).rgb;
}

// Radiance of a camera pixel that sees no surface: the map when it is the background, else the flat colour.
vec3 miss_radiance(ivec2 pixel) {
  if ((frame.environment.x & LUCENT_ENVIRONMENT_BACKGROUND) == 0) return frame.background.rgb;
  vec2 ndc = (vec2(pixel) + vec2(0.5f)) / vec2(frame.output_size.xy) * 2.0f - vec2(1.0f);
  vec4 far_point = inverse(frame.clip_from_world) * vec4(ndc, 1.0f, 1.0f);
  return environment_radiance(normalize(far_point.xyz / far_point.w - frame.camera_position.xyz), 0.0f);
}
