// lights.glsl: looking up the light G-buffer of any light type, light visibility (shadows) and the light
// arriving at a surface point. Layouts in shared/shader_io.h (LightGPU, ViewGPU); math in lights/point_light.h.
#include "lights/point_light.h"

layout(binding = LUCENT_TEX_LIGHT_POSITION) uniform sampler2DArray light_position;
layout(binding = LUCENT_TEX_LIGHT_NORMAL) uniform sampler2DArray light_normal;
layout(binding = LUCENT_TEX_LIGHT_DEPTH) uniform sampler2DArray light_depth;

// The layer and texture coordinates where the point light's G-buffer stores what it sees in direction d
// (first = first layer, count = 1 for one frustum, 6 for a cube map). False when d leaves the frustum.
bool point_light_lookup(LightGPU light, int first, int count, vec3 d, out int layer, out vec2 uv) {
  layer = first + (count == 6 ? cube_face(d) : 0);
  vec3 t = view_coords(frame.light_views[layer], light.position.xyz + d);
  uv = t.xy;
  return t.z >= 0.0f && all(greaterThanEqual(t.xy, vec2(0.0f))) && all(lessThan(t.xy, vec2(1.0f)));
}

// Unshadowed light arriving at x: unit direction toward the light and the irradiance on a surface facing it.
vec3 light_incidence(LightGPU light, vec3 x, out vec3 w_l) {
  if (int(light.position.w) == LUCENT_LIGHT_DIRECTIONAL) {
    w_l = -light.position.xyz;
    return light.power.rgb;
  }
  vec3 to_light = light.position.xyz - x;
  float d2 = max(dot(to_light, to_light), 1e-12f);
  w_l = to_light * inversesqrt(d2);
  float cone = 1.0f;
  if (int(light.position.w) == LUCENT_LIGHT_SPOT)
    cone = spot_falloff(dot(-w_l, light.axis.xyz), light.power.w, light.axis.w);
  return light.power.rgb * cone / d2;
}

// Shadow test of a surface point x with normal n against light l's scene-wide view(s), with a normal offset.
float light_visibility(int l, vec3 x, vec3 n) {
  LightGPU light = frame.lights[l];
  if (int(light.position.w) == LUCENT_LIGHT_DIRECTIONAL) {
    ViewGPU view = frame.light_views[light.views.z];
    float texel_width = view.direction.w / float(frame.light_counts.z);
    vec3 t = view_coords(view, x + 2.0f * texel_width * n);
    if (any(lessThan(t, vec3(0.0f))) || any(greaterThanEqual(t, vec3(1.0f)))) return 1.0f;
    return multisample_visibility(light_depth, t, light.views.z, frame.light_counts.z, 2.0f * texel_width / view.radiance.w,
                                  frame.light_counts.w);
  }
  // Point and spot: compare distances to the light with the first hits stored in the shadow cube map.
  vec3 to_x = x - light.position.xyz;
  float distance = length(to_x);
  float texel_angle = frame.light_views[light.views.z].radiance.w;
  vec3 offset_x = x + 2.0f * texel_angle * distance * n;
  vec3 d = offset_x - light.position.xyz;
  int layer;
  vec2 uv;
  if (!point_light_lookup(light, light.views.z, light.views.w, d, layer, uv)) return 1.0f;
  int size = frame.light_counts.z;
  int h = frame.light_counts.w / 2;
  ivec2 center = ivec2(uv * float(size));
  float own = length(d);
  float bias = 3.0f * texel_angle * own;
  float visible = 0.0f;
  // loop bound: 4 x LUCENT_MAX_LIGHTS x 7 x 7; visibility_taps <= 7 (3 where a method fixes it), once per light by at most four light loops of a stage
  for (int dy = -h; dy <= h; ++dy)
    // loop bound: 4 x LUCENT_MAX_LIGHTS x 7 x 7; the taps of one row, counted with the loop above
    for (int dx = -h; dx <= h; ++dx) {
      ivec2 p = clamp(center + ivec2(dx, dy), ivec2(0), ivec2(size - 1));
      vec4 hit = texelFetch(light_position, ivec3(p, layer), 0);
      visible += hit.w < 0.5f || own <= length(hit.xyz - light.position.xyz) + bias ? 1.0f : 0.0f;
    }
  return visible / float((2 * h + 1) * (2 * h + 1));
}
