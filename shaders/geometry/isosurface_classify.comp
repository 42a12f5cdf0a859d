// isosurface_classify.comp: per grid point, the crossing edges it owns and its cell's inside corners (masks),
// the vertices and triangles it will emit (counts, scanned into offsets next), and, when it emits anything,
// its index appended to the active list that the emit pass runs over.
#include "geometry/isosurface_grid.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std430, binding = LUCENT_BINDING_ISO_SAMPLES) readonly buffer Samples { float samples[]; };
layout(std430, binding = LUCENT_BINDING_ISO_MASKS) writeonly buffer Masks { uint masks[]; };
layout(std430, binding = LUCENT_BINDING_ISO_OFFSETS) writeonly buffer Counts { uvec2 counts[]; };
layout(std430, binding = LUCENT_BINDING_ISO_ACTIVE) writeonly buffer Active { uint active_points[]; };
layout(std430, binding = LUCENT_BINDING_ISO_DISPATCH) buffer Dispatch { IsosurfaceDispatchGPU dispatch; };

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (!is_grid_point(p)) return;
  ivec3 cells = grid_cells();
  uint i = point_index(p);

  // Step 1: the samples of the cube above the point (0 where it leaves the grid: those edges are excluded).
  float f[8];
  for (int c = 0; c < 8; ++c) {
    ivec3 q = p + mt_corner_offset(c);
    f[c] = is_grid_point(q) ? samples[point_index(q)] : 0.0f;
  }

  // Step 2: crossing edges owned by the point; inside corners and triangle count of its cell.
  uint edge_mask = 0u, cube_inside = 0u, triangles = 0u;
  for (int direction = 1; direction <= LUCENT_MT_DIRECTIONS; ++direction)
    edge_mask |= mt_edge_bit(p, cells, direction, f[0], f[direction]);
  if (all(lessThan(p, cells))) {
    for (int c = 0; c < 8; ++c)
      if (mt_inside(f[c])) cube_inside |= 1u << uint(c);
    if (cube_inside != 0u && cube_inside != 255u) triangles = uint(mt_cell_triangle_count(int(cube_inside)));
  }
  masks[i] = edge_mask | (cube_inside << 8u);
  counts[i] = uvec2(uint(bitCount(edge_mask)), triangles);

  // Step 3: points that emit anything go on the active list (drivers combine same-address atomics of a
  // subgroup; on llvmpipe a workgroup-shared counter with barriers measured slower).
  if (edge_mask != 0u || triangles != 0u) {
    uint slot = atomicAdd(dispatch.active_points, 1u);
    if (slot < params.limits.y) active_points[slot] = i;
  }
}
