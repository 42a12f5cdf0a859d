// isosurface_emit.comp: per active grid point (classify's list, in any order: the scanned offsets fix where
// everything goes), the vertices of its crossing edges and the triangles of its cell. Nothing is written past
// the capacity (the draw is then empty, see isosurface_finalize.comp).
#include "geometry/isosurface_grid.glsl"
#include "shared/shader_io.h"

layout(local_size_x = LUCENT_ISO_EMIT_GROUP) in;
layout(std430, binding = LUCENT_BINDING_ISO_SAMPLES) readonly buffer Samples { float samples[]; };
layout(std430, binding = LUCENT_BINDING_ISO_MASKS) readonly buffer Masks { uint masks[]; };
layout(std430, binding = LUCENT_BINDING_ISO_OFFSETS) readonly buffer Offsets { uvec2 offsets[]; };
layout(std430, binding = LUCENT_BINDING_ISO_VERTICES) writeonly buffer Vertices { VertexGPU vertices[]; };
layout(std430, binding = LUCENT_BINDING_ISO_INDICES) writeonly buffer Indices { uint indices[]; };
layout(std430, binding = LUCENT_BINDING_ISO_ACTIVE) readonly buffer Active { uint active_points[]; };
layout(std430, binding = LUCENT_BINDING_ISO_DISPATCH) readonly buffer Dispatch { IsosurfaceDispatchGPU dispatch; };

// The outward gradient direction, or the edge direction (inside to outside) where the gradient vanishes.
vec3 vertex_normal(vec3 position, vec3 edge_inside_to_outside) {
  vec3 outward = -blob_field_gradient_of(params.field, position);
  if (dot(outward, outward) < 1e-20f) outward = edge_inside_to_outside;
  return normalize(outward);
}

void emit_vertices(ivec3 p, uint i, uint edge_mask, uint capacity) {
  uint first = offsets[i].x;
  float f_p = samples[i];
  vec3 a = grid_position(p);
  for (int direction = 1; direction <= LUCENT_MT_DIRECTIONS; ++direction) {
    if ((edge_mask & (1u << uint(direction - 1))) == 0u) continue;
    uint slot = first + mt_vertex_rank(edge_mask, direction);
    if (slot >= capacity) return;
    ivec3 q = p + mt_corner_offset(direction);
    float f_q = samples[point_index(q)];
    vec3 b = grid_position(q);
    vec3 position = a + mt_edge_fraction(f_p, f_q) * (b - a);
    vertices[slot].position = vec4(position, params.spacing.w);
    vertices[slot].normal = vec4(vertex_normal(position, mt_inside(f_p) ? b - a : a - b), 0.0f);
    vertices[slot].uv = vec4(0.0f);  // an isosurface has no texture coordinates
  }
}

void emit_triangles(ivec3 cell, uint i, int cube_inside, uint capacity) {
  uint slot = offsets[i].y;
  for (int tet = 0; tet < LUCENT_MT_TETS_PER_CELL; ++tet) {
    int inside = mt_tet_inside_mask(tet, cube_inside);
    // loop bound: LUCENT_MT_TETS_PER_CELL x 2; marching tetrahedra emit at most two triangles per tetrahedron
    for (int t = 0; t < mt_tet_triangle_count(inside); ++t) {
      if (slot >= capacity) return;
      ivec3 edges = mt_tet_triangle(inside, mt_tet_parity(tet), t);
      for (int v = 0; v < 3; ++v) {
        int lower = mt_tet_corner(tet, edges[v] / 4), upper = mt_tet_corner(tet, edges[v] % 4);
        uint owner = point_index(cell + mt_corner_offset(lower));
        indices[3u * slot + uint(v)] = offsets[owner].x + mt_vertex_rank(masks[owner] & 127u, upper - lower);
      }
      ++slot;
    }
  }
}

void main() {
  uint k = gl_GlobalInvocationID.x;
  if (k >= min(dispatch.active_points, params.limits.y)) return;
  uint i = active_points[k];
  ivec3 p = point_from_index(i);
  uint mask = masks[i], capacity = params.limits.x;
  uint edge_mask = mask & 127u;
  int cube_inside = int((mask >> 8u) & 255u);
  if (edge_mask != 0u) emit_vertices(p, i, edge_mask, capacity);
  if (cube_inside != 0 && cube_inside != 255) emit_triangles(p, i, cube_inside, capacity);
}
