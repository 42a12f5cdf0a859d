// irradiance_sample.comp: stage 2 of texture-space importance sampling: N texels drawn with probability E'_a / E'_total,a
// (Chang et al. 2008, Eq. 9) by the inverse CDF, one invocation per sample. Stratified: sample i inverts
// u = (i + xi_i) / N. Mipmap order (Fig. 2b): one top-down descent of the sum pyramid (shared/mip_sampling.h);
// row-major order (Fig. 2a): binary search over the row totals, then within the row (irradiance_row_cdf.comp). Each sample
// stores its texel and its weight E'(texel) E'_total,a / (E'_a(texel) N) per band (Eq. 10).
#include "shared/mip_sampling.h"
#include "shared/random.h"
#include "shared/shader_io.h"
#include "shared/tsis_samples.h"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
layout(location = 0) uniform int count;
layout(location = 1) uniform int order;
layout(location = 2) uniform int size;
layout(location = 3) uniform int levels;
layout(location = 4) uniform uint seed;
layout(location = 5) uniform uint frame_index;
layout(location = 6) uniform int write_counters;
layout(binding = TSIS_TEX_PYRAMID) uniform sampler2D pyramid;
layout(std430, binding = TSIS_BINDING_SAMPLES) buffer Samples {
  vec4 total;
  TsisSampleGPU samples[];
};
layout(std430, binding = TSIS_BINDING_ROW_CDF) readonly buffer RowCdf { float cdf[]; };
layout(std430, binding = LUCENT_BINDING_COUNTERS) buffer CounterBlock { CountersGPU counters; };

// First index in [first, first + n) whose cdf exceeds target (n when none).
int search(int first, int n, float target) {
  int lo = 0, hi = n;
  // loop bound: 2 x 13; two binary searches over atlas_size <= 4096 entries (at most log2(4096) + 1 steps each)
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (cdf[first + mid] > target) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= count) return;
  vec4 sum = texelFetch(pyramid, ivec2(0), levels - 1);
  if (i == 0) {
    total = sum;
    if (write_counters != 0) counters.method_counts[1] = floatBitsToUint(sum.a);
  }
  float u = (float(i) + next_float(seed_from(seed, uint(i), 0x7e5u, frame_index))) / float(count);
  ivec2 t = ivec2(0);
  if (order == LUCENT_TSIS_ORDER_ROW_MAJOR) {
    float rows_total = cdf[size * size + size - 1];
    float target = u * rows_total;
    int y = min(search(size * size, size, target), size - 1);
    float before = y > 0 ? cdf[size * size + y - 1] : 0.0f;
    int x = min(search(y * size, size, target - before), size - 1);
    t = ivec2(x, y);
  } else {
    // loop bound: 13; the levels of the irradiance pyramid of an atlas of at most 4096^2 texels
    for (int level = levels - 2; level >= 0; --level) {
      ivec2 c = 2 * t;
      vec4 w = vec4(texelFetch(pyramid, c, level).a, texelFetch(pyramid, c + ivec2(1, 0), level).a,
                    texelFetch(pyramid, c + ivec2(0, 1), level).a, texelFetch(pyramid, c + ivec2(1, 1), level).a);
      MipChoice choice = mip_choose_child(w, u);
      t = c + mip_child_offset(choice.child);
      u = choice.u;
    }
  }
  vec4 e = texelFetch(pyramid, t, 0);
  TsisSampleGPU s;
  s.texel = ivec4(t, 0, 0);
  s.weight = e.a > 0.0f ? vec4(e.rgb * (sum.a / (e.a * float(count))), 0.0f) : vec4(0.0f);
  samples[i] = s;
}
