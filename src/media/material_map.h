// material_map.h: the texture lookup of textured materials (lucent::MaterialMaps), written once for C++ and GLSL:
// bilinear between texel centres, repeating outside [0, 1], rows from v = 0 (OpenGL's origin) up, x fastest.
//
// On the GPU a material's maps are slices of one vec4 array in the storage buffer LUCENT_BINDING_MATERIAL_MAPS
// (render/scene_gpu.cpp uploads it; xyz per texel, w unused), described in MaterialGPU by alpha_map and mfp_map:
// x the first texel (-1: no map), y and z the width and height. alpha texels hold the single-scattering albedo
// sigma_s / sigma_t, mfp texels the mean free path 1 / sigma_t in scene units. Shaders that read maps compile with
// LUCENT_MATERIAL_MAPS (render::light_sampling_defines sets it for scenes that have them).
#ifndef LUCENT_MEDIA_MATERIAL_MAP_H
#define LUCENT_MEDIA_MATERIAL_MAP_H
#include "shared/bridge.h"
#include "shared/bindings.h"
#include "shared/shader_io.h"

LUCENT_SHADER_BEGIN

// The four texels of a bilinear lookup and their weights (summing to 1).
struct MapTaps {
  ivec4 index;  // row-major texel indices: (x0, y0), (x1, y0), (x0, y1), (x1, y1)
  vec4 weight;
};

LUCENT_INLINE MapTaps material_map_taps(vec2 uv, ivec2 size) {
  // Coordinates beyond a float's reach of [0, 1] (NaN too, from degenerate geometry) read at 0.
  if (!(abs(uv.x) < 1e6f)) uv.x = 0.0f;
  if (!(abs(uv.y) < 1e6f)) uv.y = 0.0f;
  vec2 p = fract(uv) * vec2(float(size.x), float(size.y)) - vec2(0.5f);  // texel centres at integers
  vec2 p0 = floor(p);
  vec2 t = p - p0;
  int x0 = int(p0.x), y0 = int(p0.y);
  int x1 = x0 + 1, y1 = y0 + 1;
  if (x0 < 0) x0 += size.x;  // p0 >= -1: one wrap at either end suffices
  if (y0 < 0) y0 += size.y;
  if (x1 >= size.x) x1 -= size.x;
  if (y1 >= size.y) y1 -= size.y;
  // In range already; the clamps keep a NaN that a driver's fast math let through inside the map.
  x0 = clamp(x0, 0, size.x - 1);
  x1 = clamp(x1, 0, size.x - 1);
  y0 = clamp(y0, 0, size.y - 1);
  y1 = clamp(y1, 0, size.y - 1);
  MapTaps taps;
  taps.index = ivec4(y0 * size.x + x0, y0 * size.x + x1, y1 * size.x + x0, y1 * size.x + x1);
  taps.weight = vec4((1.0f - t.x) * (1.0f - t.y), t.x * (1.0f - t.y), (1.0f - t.x) * t.y, t.x * t.y);
  return taps;
}

LUCENT_SHADER_END

#if !defined(__cplusplus) && (defined(LUCENT_MATERIAL_MAPS) || defined(LUCENT_THICKNESS_FIELDS))
// Also holds the multipole model's thickness grids (geometry/thickness_field.h).
layout(std430, binding = LUCENT_BINDING_MATERIAL_MAPS) readonly buffer MaterialMapBlock { vec4 material_map_texels[]; };
#endif

#if !defined(__cplusplus) && defined(LUCENT_MATERIAL_MAPS)

// The value of the map `map` (MaterialGPU's alpha_map or mfp_map) at uv.
vec3 material_map_value(ivec4 map, vec2 uv) {
  MapTaps taps = material_map_taps(uv, map.yz);
  return taps.weight.x * material_map_texels[map.x + taps.index.x].xyz +
         taps.weight.y * material_map_texels[map.x + taps.index.y].xyz +
         taps.weight.z * material_map_texels[map.x + taps.index.z].xyz +
         taps.weight.w * material_map_texels[map.x + taps.index.w].xyz;
}

// The material with its coefficients at texture coordinates uv (unchanged without maps).
MaterialGPU material_at(MaterialGPU m, vec2 uv) {
  if (m.alpha_map.x < 0 && m.mfp_map.x < 0) return m;
  vec3 sigma_t = m.sigma_a.xyz + m.sigma_s.xyz;
  vec3 alpha = m.alpha_map.x >= 0 ? material_map_value(m.alpha_map, uv) : m.sigma_s.xyz / sigma_t;
  vec3 mfp = m.mfp_map.x >= 0 ? material_map_value(m.mfp_map, uv) : 1.0f / sigma_t;
  m.sigma_s.xyz = alpha / mfp;
  m.sigma_a.xyz = (1.0f - alpha) / mfp;
  return m;
}
#endif

#endif  // LUCENT_MEDIA_MATERIAL_MAP_H
