// combine.comp: step 3 of Dal Corso et al. 2015: per camera pixel, Algorithm 1 (K map look-ups weighted by
// multi-sampled visibility from each map's depth with eps_bias, positions offset by eps_comb), then the
// outgoing radiance of eq. 5, L_o = F_t(w_o) B / pi, plus optional GGX specular reflection of the lights.
// Opaque objects get Lambertian direct light with shadows from the light G-buffer depth.
#include "common/frame.glsl"
#include "brdf/ggx.h"
#include "bssrdf/fresnel.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(binding = LUCENT_TEX_CAMERA_POSITION) uniform sampler2D camera_position;
layout(binding = LUCENT_TEX_CAMERA_NORMAL) uniform sampler2D camera_normal;
layout(binding = LUCENT_TEX_LIGHT_DEPTH) uniform sampler2DArray light_depth;
layout(binding = LUCENT_TEX_MAP_DEPTH) uniform sampler2DArray map_depth;
layout(binding = LUCENT_TEX_RADIOSITY) uniform sampler2DArray radiosity;
layout(rgba32f, binding = LUCENT_IMAGE_HDR) uniform writeonly image2D hdr;

// Fraction of the (2h+1)^2 depth taps around t for which the point at depth t.z is visible.
float multisample_visibility(sampler2DArray depth, vec3 t, int layer, int size, float bias) {
  int h = frame.counts.w / 2;
  ivec2 center = ivec2(t.xy * float(size));
  float visible = 0.0f;
  for (int dy = -h; dy <= h; ++dy)
    for (int dx = -h; dx <= h; ++dx) {
      ivec2 p = clamp(center + ivec2(dx, dy), ivec2(0), ivec2(size - 1));
      visible += t.z <= texelFetch(depth, ivec3(p, layer), 0).r + bias ? 1.0f : 0.0f;
    }
  return visible / float((2 * h + 1) * (2 * h + 1));
}

// Visible taps of the (2h+1)^2 neighbourhood of map k at t: a tap counts when x_bar is not behind the surface
// stored there (depth test with bias); its radiosity is the texel's mean over frames. Taps are tested
// individually so that a texel of an occluding surface never blends into x_o (bilinear filtering did, and drew
// bright seams where one object occludes another in a map view).
vec4 visible_taps(int k, vec3 t, float bias) {
  int size = frame.sizes.x;
  int h = frame.counts.w / 2;
  ivec2 center = ivec2(t.xy * float(size));
  vec3 sum = vec3(0.0f);
  float visible = 0.0f;
  for (int dy = -h; dy <= h; ++dy)
    for (int dx = -h; dx <= h; ++dx) {
      ivec3 p = ivec3(clamp(center + ivec2(dx, dy), ivec2(0), ivec2(size - 1)), k);
      if (t.z > texelFetch(map_depth, p, 0).r + bias) continue;
      vec4 accumulated = texelFetch(radiosity, p, 0);
      if (accumulated.a <= 0.0f) continue;
      sum += accumulated.rgb / accumulated.a;
      visible += 1.0f;
    }
  return vec4(sum, visible) / float((2 * h + 1) * (2 * h + 1));
}

// Algorithm 1: scattered radiosity at x_o from the K maps; coverage in w (0 = seen by no map).
// filter_lod = 0: per-tap visibility and radiosity (visible_taps); filter_lod > 0: multi-sampled visibility
// and a mip-filtered look-up (the paper's noise filter), normalised by the filtered frame count.
vec4 combine_maps(vec3 x_o, vec3 n_o) {
  int size = frame.sizes.x;
  vec3 color = vec3(0.0f);
  float n = 0.0f;
  for (int k = 0; k < frame.counts.y; ++k) {
    vec3 d_k = frame.maps[k].direction.xyz;
    float texel_width = frame.maps[k].direction.w / float(size);
    float cos_theta = clamp(dot(n_o, d_k), 0.0f, 1.0f);
    vec3 x_bar = x_o - frame.biases.y * texel_width * (n_o - cos_theta * d_k);
    vec3 t = view_texture_coords(frame.maps[k].clip_from_world, x_bar);
    if (any(lessThan(t.xy, vec2(0.0f))) || any(greaterThanEqual(t.xy, vec2(1.0f)))) continue;
    // Depth spans the view width, so eps_bias texels are eps_bias / size in depth units.
    float bias = frame.biases.x / float(size);
    if (frame.biases.z <= 0.0f) {
      vec4 taps = visible_taps(k, t, bias);
      color += taps.rgb;
      n += taps.w;
      continue;
    }
    float v = multisample_visibility(map_depth, t, k, size, bias);
    if (v <= 0.0f) continue;
    vec4 accumulated = textureLod(radiosity, vec3(t.xy, float(k)), frame.biases.z);
    if (accumulated.a <= 0.0f) continue;
    color += v * accumulated.rgb / accumulated.a;  // mean over frames, normalised by filtered coverage
    n += v;
  }
  return n > 0.0f ? vec4(color / n, 1.0f) : vec4(0.0f);
}

// Shadow test in the scene-wide view of light l (light G-buffer layer L + l), normal offset of 2 texels.
float light_visibility(int l, vec3 x, vec3 n) {
  ViewGPU view = frame.shadows[l];
  float texel_width = view.direction.w / float(frame.sizes.y);
  vec3 t = view_texture_coords(view.clip_from_world, x + 2.0f * texel_width * n);
  if (any(lessThan(t, vec3(0.0f))) || any(greaterThanEqual(t, vec3(1.0f)))) return 1.0f;
  return multisample_visibility(light_depth, t, frame.counts.x + l, frame.sizes.y, 2.0f * texel_width / view.radiance.w);
}

vec3 shade_opaque(vec3 x, vec3 n, vec3 albedo) {
  vec3 L = vec3(0.0f);
  for (int l = 0; l < frame.counts.x; ++l) {
    float cos_l = dot(n, -frame.lights[l].direction.xyz);
    if (cos_l <= 0.0f) continue;
    L += albedo * kInvPi * frame.lights[l].radiance.rgb * cos_l * light_visibility(l, x, n);
  }
  return L;
}

vec3 shade_translucent(vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  float eta = material.sigma_a.w;
  vec4 B = combine_maps(x, n);
  if (int(frame.options.y) == LUCENT_VIEW_COVERAGE) return B.w > 0.0f ? vec3(0.2f) : vec3(1.0f, 0.0f, 1.0f);
  vec3 L = fresnel_transmittance(eta, dot(n, w_o)) * kInvPi * B.rgb;
  if (frame.options.z > 0.5f) {
    for (int l = 0; l < frame.counts.x; ++l) {
      vec3 w_l = -frame.lights[l].direction.xyz;
      float f_r = ggx_dielectric_brdf(n, w_l, w_o, frame.biases.w, eta);
      L += f_r * max(dot(n, w_l), 0.0f) * frame.lights[l].radiance.rgb * light_visibility(l, x, n);
    }
  }
  return L;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.sizes.z || pixel.y >= frame.sizes.w) return;
  vec4 p = texelFetch(camera_position, pixel, 0);
  if (p.w < 0.5f) {
    imageStore(hdr, pixel, vec4(frame.background.rgb, 0.0f));
    return;
  }
  ObjectGPU object = objects[int(p.w) - 1];
  vec3 n = normalize(texelFetch(camera_normal, pixel, 0).xyz);
  vec3 w_o = normalize(frame.camera_position.xyz - p.xyz);
  vec3 L;
  if (object.info.x < 0) {
    if (dot(n, w_o) < 0.0f) n = -n;  // two-sided opaque surfaces (planes seen from below)
    L = shade_opaque(p.xyz, n, object.albedo.rgb);
  } else {
    L = shade_translucent(p.xyz, n, w_o, materials[object.info.x]);
  }
  imageStore(hdr, pixel, vec4(L, 1.0f));
}
