// thickness_field.h: the multipole model's thickness per surface point (lucent::ThicknessGrid, built from the shape
// diameter of each triangle when a material says "thickness_from_mesh"), looked up alike in C++ and GLSL:
// trilinear over the eight nodes of the cell around a point, the nodes without a value (0: no surface near them)
// left out and the others' weights renormalised; where none of the eight has a value, or outside the grid, the
// object's median thickness.
//
// On the GPU a grid is a slice of the vec4 storage buffer LUCENT_BINDING_MATERIAL_MAPS (render/scene_gpu.cpp
// appends it after the textured materials' maps), found through ObjectGPU.info.y (-1: the object has none):
//   texel info.y:      the first node's position xyz [scene units]; w: 1 / node spacing [1/scene unit]
//   texel info.y + 1:  the node counts along x, y, z (as floats); w: the fallback thickness [scene units]
//   texels after them: the node values [scene units], four per texel, x fastest, then y, then z.
// Shaders that read grids compile with LUCENT_THICKNESS_FIELDS (render::light_sampling_defines sets it). C++ builds
// and reads grids through geometry/thickness_grid.h.
#ifndef LUCENT_GEOMETRY_THICKNESS_FIELD_H
#define LUCENT_GEOMETRY_THICKNESS_FIELD_H
#include "shared/bridge.h"

LUCENT_SHADER_BEGIN

// The cell of a grid around x: its lowest node's index (-1 outside the grid), the index steps along x, y, z and
// x's position inside the cell (0..1 per axis). `header0` and `header1` are the grid's two header texels.
struct ThicknessCell {
  int node;
  ivec3 stride;
  vec3 t;
};

LUCENT_INLINE ThicknessCell thickness_cell(vec3 x, vec4 header0, vec4 header1) {
  ThicknessCell c;
  ivec3 n = ivec3(vec3(header1));
  vec3 p = (x - vec3(header0)) * header0.w;
  c.node = -1;
  c.stride = ivec3(1, n.x, n.x * n.y);
  c.t = vec3(0.0f);
  vec3 last = vec3(n - ivec3(1));
  // Written so that NaN coordinates fall outside.
  if (!(p.x >= 0.0f && p.y >= 0.0f && p.z >= 0.0f && p.x <= last.x && p.y <= last.y && p.z <= last.z)) return c;
  vec3 p0 = min(floor(p), last - vec3(1.0f));  // a point on the far face belongs to the last cell
  c.t = p - p0;
  ivec3 i = ivec3(p0);
  c.node = i.x + c.stride.y * i.y + c.stride.z * i.z;
  return c;
}

// The thickness from the cell's node values: `lower` the four at the cell's lower z, `upper` at its upper z, each
// ordered (x0 y0, x1 y0, x0 y1, x1 y1). Nodes holding 0 have no value and no weight.
LUCENT_INLINE float thickness_blend(vec4 lower, vec4 upper, vec3 t, float fallback) {
  vec4 w_xy = vec4((1.0f - t.x) * (1.0f - t.y), t.x * (1.0f - t.y), (1.0f - t.x) * t.y, t.x * t.y);
  vec4 w_lower = w_xy * (1.0f - t.z) * step(vec4(1e-30f), lower);
  vec4 w_upper = w_xy * t.z * step(vec4(1e-30f), upper);
  float weight = dot(w_lower, vec4(1.0f)) + dot(w_upper, vec4(1.0f));
  if (!(weight > 0.0f)) return fallback;
  return (dot(w_lower, lower) + dot(w_upper, upper)) / weight;
}

LUCENT_SHADER_END

#if !defined(__cplusplus) && defined(LUCENT_THICKNESS_FIELDS)
// Needs media/material_map.h's buffer (declared there when LUCENT_THICKNESS_FIELDS is set).
float thickness_node(int grid, int node) { return material_map_texels[grid + 2 + node / 4][node % 4]; }

float thickness_at(int grid, vec3 x) {
  vec4 header0 = material_map_texels[grid], header1 = material_map_texels[grid + 1];
  ThicknessCell c = thickness_cell(x, header0, header1);
  if (c.node < 0) return header1.w;
  int n = c.node, sx = c.stride.x, sy = c.stride.y, sz = c.stride.z;
  vec4 lower = vec4(thickness_node(grid, n), thickness_node(grid, n + sx), thickness_node(grid, n + sy),
                    thickness_node(grid, n + sx + sy));
  vec4 upper = vec4(thickness_node(grid, n + sz), thickness_node(grid, n + sx + sz), thickness_node(grid, n + sy + sz),
                    thickness_node(grid, n + sx + sy + sz));
  return thickness_blend(lower, upper, c.t, header1.w);
}
#endif

#if !defined(__cplusplus)
// The multipole model's reflection thickness at x on an object (its ObjectGPU.info) whose material states
// `material_thickness` (MaterialGPU.g.w): the object's grid where it has one.
float surface_thickness(ivec4 object_info, float material_thickness, vec3 x) {
#if defined(LUCENT_THICKNESS_FIELDS)
  if (object_info.y >= 0) return thickness_at(object_info.y, x);
#endif
  return material_thickness;
}
#endif

#endif
