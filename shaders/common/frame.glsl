// frame.glsl: the frame's uniform block (common to every method) and the scene's material and object buffers
// (layouts in shared/shader_io.h, binding points in shared/bindings.h).
#include "shared/shader_io.h"

layout(std140, binding = LUCENT_BINDING_FRAME) uniform FrameBlock { FrameGPU frame; };
layout(std430, binding = LUCENT_BINDING_MATERIALS) readonly buffer MaterialBlock { MaterialGPU materials[]; };
layout(std430, binding = LUCENT_BINDING_OBJECTS) readonly buffer ObjectBlock { ObjectGPU objects[]; };

// Texture coordinates (u, v, depth in [0, 1]) of a world point in a view; z < 0 when behind a perspective view.
vec3 view_coords(ViewGPU view, vec3 x) {
  vec4 clip = view.clip_from_world * vec4(x, 1.0f);
  if (clip.w <= 0.0f) return vec3(-1.0f);
  return 0.5f * clip.xyz / clip.w + vec3(0.5f);
}

// Cube face of a direction: 0 +X, 1 -X, 2 +Y, 3 -Y, 4 +Z, 5 -Z (the order the CPU builds the face views in).
int cube_face(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0f ? 0 : 1;
  if (a.y >= a.z) return d.y >= 0.0f ? 2 : 3;
  return d.z >= 0.0f ? 4 : 5;
}

// Fraction of the taps x taps orthographic depth taps around t for which the point at depth t.z is visible.
float multisample_visibility(sampler2DArray depth, vec3 t, int layer, int size, float bias, int taps) {
  int h = taps / 2;
  ivec2 center = ivec2(t.xy * float(size));
  float visible = 0.0f;
  // loop bound: LUCENT_MAX_MAPS x 7 x 7; taps <= 7 (visibility_taps' range; 3 where a method fixes it), called once per map (K <= LUCENT_MAX_MAPS) or per light by a few light loops (<= 4 x LUCENT_MAX_LIGHTS)
  for (int dy = -h; dy <= h; ++dy)
    // loop bound: LUCENT_MAX_MAPS x 7 x 7; the taps of one row, counted with the loop above
    for (int dx = -h; dx <= h; ++dx) {
      ivec2 p = clamp(center + ivec2(dx, dy), ivec2(0), ivec2(size - 1));
      visible += t.z <= texelFetch(depth, ivec3(p, layer), 0).r + bias ? 1.0f : 0.0f;
    }
  return visible / float((2 * h + 1) * (2 * h + 1));
}
