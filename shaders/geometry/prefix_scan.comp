// prefix_scan.comp: exclusive prefix sum of uvec2 values in place, one block of LUCENT_SCAN_BLOCK elements per
// workgroup (4 per invocation, then a Hillis-Steele scan of the invocation totals in shared memory); each
// block's total goes to sums[block]. Blocks are joined by scanning the sums and prefix_scan_add.comp.
#include "geometry/isosurface_io.h"

layout(local_size_x = 256) in;
layout(std430, binding = LUCENT_BINDING_SCAN_DATA) buffer Data { uvec2 data[]; };
layout(std430, binding = LUCENT_BINDING_SCAN_SUMS) writeonly buffer Sums { uvec2 sums[]; };
layout(location = 0) uniform uint count;

shared uvec2 partial[256];

void main() {
  uint local = gl_LocalInvocationID.x;
  uint first = gl_WorkGroupID.x * uint(LUCENT_SCAN_BLOCK) + 4u * local;
  uvec2 values[4];
  uvec2 total = uvec2(0u);
  for (uint k = 0u; k < 4u; ++k) {
    uvec2 v = first + k < count ? data[first + k] : uvec2(0u);
    values[k] = total;  // exclusive within the invocation
    total += v;
  }
  partial[local] = total;
  barrier();
  for (uint offset = 1u; offset < 256u; offset <<= 1u) {
    uvec2 add = local >= offset ? partial[local - offset] : uvec2(0u);
    barrier();
    partial[local] += add;
    barrier();
  }
  uvec2 before = partial[local] - total;  // exclusive over the invocations of the block
  for (uint k = 0u; k < 4u; ++k)
    if (first + k < count) data[first + k] = values[k] + before;
  if (local == 255u) sums[gl_WorkGroupID.x] = partial[255];
}
