// shade.comp: multi-layer parallax shading (Oat 2006 as in Norberg 2010, Section 2.2.3) per camera pixel on a
// translucent object. In the tangent frame (T, B from the gradients of u and v, N the geometric normal):
//   outer layer: base colour and see-through weight a, normal N' from the normal map, lit directly (E N'.L / pi);
//   inner layer: R = -V - 2 (-V . N') N' (Eq. 15), T = (R_x, R_y, -R_z) (Eq. 16), s = d / |T_z| (Eq. 17),
//                uv' = uv + s (T_x, T_y) in texture units (Eq. 18: the tangent-frame offset times |grad u|, |grad v|),
//                its base colour blurred by a Poisson disc of radius proportional to s, lit by the blurred
//                texture-space light map at uv;
//   blend: x (1 - w) + y w with w = a saturate(N'.V) (Eq. 19).
// The disc is rotated randomly per pixel and frame, and the frames are averaged while nothing moves. A look: the
// colours are the textures', the light is Lambertian, and nothing here is the material's physics.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "shared/random.h"
#include "media/layer_parallax.h"
#include "methods/layered_parallax/layered_parallax_io.h"
#include "methods/layered_parallax/shaders/poisson_disc.glsl"
#include "common/camera_pixel.glsl"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LayeredParallaxGPU method; };
layout(rgba32f, binding = LUCENT_IMAGE_LPAR_SUM) uniform image2D accumulated;  // rgb: sum of radiance, a: frames
layout(binding = LUCENT_TEX_LPAR_OUTER_BASE) uniform sampler2D outer_base;
layout(binding = LUCENT_TEX_LPAR_OUTER_NORMAL) uniform sampler2D outer_normal;
layout(binding = LUCENT_TEX_LPAR_INNER_BASE) uniform sampler2D inner_base;
layout(binding = LUCENT_TEX_LPAR_LIGHT_MAP) uniform sampler2DArray light_map;
layout(binding = LUCENT_TEX_LPAR_SURFACE) uniform sampler2D surface;
layout(binding = LUCENT_TEX_LPAR_GRADIENT_U) uniform sampler2D gradient_u;
layout(binding = LUCENT_TEX_LPAR_GRADIENT_V) uniform sampler2D gradient_v;

vec3 shade(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, vec2 uv_mesh, vec3 gu, vec3 gv, uint seed) {
  float tiling = method.layers.y;
  vec2 uv = tiling * uv_mesh;
  // Tangent frame; an arbitrary one where the mesh has no texture coordinates (zero gradients).
  vec3 t = gu - n * dot(gu, n);
  if (!(dot(t, t) > 0.0f)) t = abs(n.x) < 0.9f ? cross(n, vec3(1.0f, 0.0f, 0.0f)) : cross(n, vec3(0.0f, 1.0f, 0.0f));
  t = normalize(t);
  vec3 b = cross(n, t);
  if (dot(b, gv) < 0.0f) b = -b;
  vec4 outer = textureLod(outer_base, uv, 0.0f);
  vec3 normal_t = normalize(textureLod(outer_normal, uv, 0.0f).xyz);
  vec3 normal_w = normalize(normal_t.x * t + normal_t.y * b + normal_t.z * n);
  vec3 view_t = vec3(dot(w_o, t), dot(w_o, b), dot(w_o, n));
  // Outer layer, lit directly through its normal map.
  vec3 E_outer = vec3(0.0f);
  // loop bound: LUCENT_MAX_LIGHTS x 7 x 7; at most LUCENT_MAX_LIGHTS lights, each with at most 7 x 7 shadow taps
  for (int l = 0; l < frame.light_counts.x; ++l) {
    vec3 w_l;
    vec3 incident = light_incidence(frame.lights[l], x, w_l);
    float cos_l = dot(normal_w, w_l);
    if (cos_l > 0.0f && dot(n, w_l) > 0.0f) E_outer += incident * cos_l * light_visibility(l, x, n);
  }
  // Inner layer: transmission vector and parallax offset (Eqs. 15-18).
  vec3 offset = parallax_offset(parallax_transmission(view_t, normal_t), method.layers.x, 0.05f);
  float s = offset.z;
  vec2 uv_inner = uv + vec2(offset.x * tiling * length(gu), offset.y * tiling * length(gv));
  float radius = method.layers.w * s;
  float angle = 6.2831853f * next_float(seed);
  mat2 rotation = mat2(cos(angle), sin(angle), -sin(angle), cos(angle));
  vec3 inner = vec3(0.0f);
  for (int i = 0; i < kPoissonTaps; ++i) inner += textureLod(inner_base, uv_inner + radius * (rotation * kPoissonDisc[i]), 0.0f).rgb;
  inner /= float(kPoissonTaps);
  vec4 light = textureLod(light_map, vec3(uv_mesh, float(object_index)), 0.0f);
  vec3 E_inner = light.a > 0.0f ? light.rgb / light.a : vec3(0.0f);
  // Blend (Eq. 19 and Section 2.2.3).
  vec3 x_outer = outer.rgb * E_outer * kInvPi;
  vec3 y_inner = inner * E_inner * kInvPi;
  float w = parallax_inner_weight(outer.a, normal_w, w_o);
  return mix(x_outer, y_inner, w);
}

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  vec4 s = texelFetch(surface, pixel, 0);
  if (s.w < 0.5f || int(s.z + 0.5f) != object_index + 1) return vec4(0.0f);
  vec3 gu = texelFetch(gradient_u, pixel, 0).xyz, gv = texelFetch(gradient_v, pixel, 0).xyz;
  uint point = uint(pixel.y * frame.output_size.x + pixel.x);
  uint seed = seed_from(frame.seeds.x, point, frame.seeds.y, 0x4C50u);
  vec3 estimate = shade(pixel, object_index, x, n, w_o, s.xy, gu, gv, seed);
  vec4 sum = frame.seeds.z != 0u ? vec4(0.0f) : imageLoad(accumulated, pixel);
  sum += vec4(estimate, 1.0f);
  imageStore(accumulated, pixel, sum);
  return vec4(sum.rgb / sum.a, 1.0f);
}
