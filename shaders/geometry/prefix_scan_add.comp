// prefix_scan_add.comp: adds each block's scanned offset (sums[block], already an exclusive scan of the block
// totals) to the block's elements, completing a multi-block prefix_scan.comp.
#include "geometry/isosurface_io.h"

layout(local_size_x = 256) in;
layout(std430, binding = LUCENT_BINDING_SCAN_DATA) buffer Data { uvec2 data[]; };
layout(std430, binding = LUCENT_BINDING_SCAN_SUMS) readonly buffer Sums { uvec2 sums[]; };
layout(location = 0) uniform uint count;

void main() {
  uvec2 add = sums[gl_WorkGroupID.x];
  uint first = gl_WorkGroupID.x * uint(LUCENT_SCAN_BLOCK) + 4u * gl_LocalInvocationID.x;
  for (uint k = 0u; k < 4u; ++k)
    if (first + k < count) data[first + k] += add;
}
