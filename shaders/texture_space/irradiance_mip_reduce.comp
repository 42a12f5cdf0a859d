// irradiance_mip_reduce.comp: one level of the E' sum pyramid: each texel of the target level is the sum of its four
// children in the source level (all four channels; a is the sampled density).
#include "shared/tsis_samples.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rgba32f, binding = TSIS_IMAGE_SOURCE) uniform readonly image2D source;
layout(rgba32f, binding = TSIS_IMAGE_TARGET) uniform writeonly image2D target;

void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(t, imageSize(target)))) return;
  ivec2 c = 2 * t;
  vec4 sum = imageLoad(source, c) + imageLoad(source, c + ivec2(1, 0)) + imageLoad(source, c + ivec2(0, 1)) +
             imageLoad(source, c + ivec2(1, 1));
  imageStore(target, t, sum);
}
