// irradiance_row_cdf.comp: the row-major CDF of E'_a (Chang et al. 2008, Fig. 2a) as two levels: cdf[y * P + x] the
// inclusive prefix sum of row y up to x, cdf[P * P + y] the inclusive prefix sum of the row totals up to row y.
// One work group: each invocation sums its rows, then the first one the row totals.
#include "shared/tsis_samples.h"

layout(local_size_x = 256, local_size_y = 1, local_size_z = 1) in;
layout(location = 0) uniform int size;
layout(rgba32f, binding = TSIS_IMAGE_SOURCE) uniform readonly image2D level0;
layout(std430, binding = TSIS_BINDING_ROW_CDF) buffer RowCdf { float cdf[]; };

void main() {
  for (int y = int(gl_LocalInvocationID.x); y < size; y += 256) {
    float sum = 0.0f;
    for (int x = 0; x < size; ++x) {
      sum += imageLoad(level0, ivec2(x, y)).a;
      cdf[y * size + x] = sum;
    }
    cdf[size * size + y] = sum;
  }
  memoryBarrierBuffer();
  barrier();
  if (gl_LocalInvocationID.x != 0u) return;
  float sum = 0.0f;
  for (int y = 0; y < size; ++y) {
    sum += cdf[size * size + y];
    cdf[size * size + y] = sum;
  }
}
