// mip_sampling.h: the top-down descent of a sum pyramid (Chang et al. 2008, Fig. 2b, "mipmap-based order"), C++
// and GLSL. Each texel of level k+1 holds the sum of its four children at level k; a uniform number u in [0, 1)
// picks a child with probability proportional to its sum (children in the order (0,0), (1,0), (0,1), (1,1)) and
// is rescaled to [0, 1) inside that child's interval, so one u descending from the 1 x 1 top level to level 0
// lands on texel t with probability value(t) / total: the inverse CDF in mipmap order.
#ifndef LUCENT_SHARED_MIP_SAMPLING_H
#define LUCENT_SHARED_MIP_SAMPLING_H
#include "shared/bridge.h"

LUCENT_SHADER_BEGIN

struct MipChoice {
  int child;  // 0..3: offset (child & 1, child >> 1) from twice the parent's texel
  float u;    // rescaled to [0, 1) within the child's interval
};

// One step of the descent: the child of weights w (>= 0, in child order) that u falls into.
LUCENT_INLINE MipChoice mip_choose_child(vec4 w, float u) {
  MipChoice c;
  float target = u * (w.x + w.y + w.z + w.w);
  float acc = 0.0f;
  c.child = -1;
  for (int i = 0; i < 4; ++i) {
    if (w[i] > 0.0f && target < acc + w[i]) {
      c.child = i;
      break;
    }
    acc += w[i];
  }
  // Rounding past the end: the last child with non-zero weight.
  if (c.child < 0) c.child = w.w > 0.0f ? 3 : (w.z > 0.0f ? 2 : (w.y > 0.0f ? 1 : 0));
  float before = 0.0f;
  // loop bound: 3; the children before the chosen one of a 2 x 2 quad
  for (int i = 0; i < c.child; ++i) before += w[i];
  float width = w[c.child];
  c.u = width > 0.0f ? clamp((target - before) / width, 0.0f, 0.99999994f) : 0.0f;
  return c;
}

LUCENT_INLINE ivec2 mip_child_offset(int child) { return ivec2(child & 1, child >> 1); }

LUCENT_SHADER_END

#endif
