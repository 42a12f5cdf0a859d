// irradiance_row_cdf.comp: the row-major CDF of E'_a (Chang et al. 2008, Fig. 2a) as two levels: cdf[y * P + x] the
// inclusive prefix sum of row y up to x, cdf[P * P + y] the inclusive prefix sum of the row totals up to row y.
// Two dispatches: `stage` 0, one invocation per row sums it; stage 1, one invocation sums the row totals. One row
// per invocation keeps each invocation's loop at P <= 4096 iterations, under llvmpipe's loop cap
// (platform::kLlvmpipeLoopIterations), which 256 invocations of 16 rows each passed at P = 4096.
#include "shared/tsis_samples.h"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
layout(location = 0) uniform int size;
layout(location = 1) uniform int stage;
layout(rgba32f, binding = TSIS_IMAGE_SOURCE) uniform readonly image2D level0;
layout(std430, binding = TSIS_BINDING_ROW_CDF) buffer RowCdf { float cdf[]; };

void main() {
  int y = int(gl_GlobalInvocationID.x);
  float sum = 0.0f;
  if (stage == 0) {
    if (y >= size) return;
    // loop bound: 4096; one row of the irradiance pyramid's base, atlas_size <= 4096 (methods' parameter ranges)
    for (int x = 0; x < size; ++x) {
      sum += imageLoad(level0, ivec2(x, y)).a;
      cdf[y * size + x] = sum;
    }
    cdf[size * size + y] = sum;
    return;
  }
  if (y != 0) return;
  // loop bound: 4096; the rows of the irradiance pyramid's base, atlas_size <= 4096
  for (int row = 0; row < size; ++row) {
    sum += cdf[size * size + row];
    cdf[size * size + row] = sum;
  }
}
