// isosurface_finalize.comp: from the scan's totals, the overflow flag and the indirect draw command (an empty
// draw when the surface needs more than the capacity); from classify's active count, the emit dispatch.
#include "geometry/isosurface_grid.glsl"

layout(local_size_x = 1) in;
layout(std430, binding = LUCENT_BINDING_ISO_COUNTS) buffer Counts { IsosurfaceCountsGPU counts; };
layout(std430, binding = LUCENT_BINDING_ISO_DRAW) writeonly buffer Draw { DrawElementsIndirectGPU draw; };
layout(std430, binding = LUCENT_BINDING_ISO_DISPATCH) buffer Dispatch { IsosurfaceDispatchGPU dispatch; };

void main() {
  uvec4 totals = counts.totals;  // xy written by the last scan level
  uint capacity = params.limits.x;
  bool over = totals.x > capacity || totals.y > capacity;
  counts.totals = uvec4(totals.xy, over ? 1u : 0u, 0u);
  draw.count = over ? 0u : 3u * totals.y;
  draw.instance_count = 1u;
  draw.first_index = 0u;
  draw.base_vertex = 0;
  draw.base_instance = 0u;
  uint listed = min(dispatch.active_points, params.limits.y);
  dispatch.groups_x = (listed + uint(LUCENT_ISO_EMIT_GROUP) - 1u) / uint(LUCENT_ISO_EMIT_GROUP);
  dispatch.groups_y = 1u;
  dispatch.groups_z = 1u;
}
