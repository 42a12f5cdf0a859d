// resolve.comp: a batch's finished paths (the current results region) into the image: per pixel, the sum of its paths' radiance (in sample
// order, so the image does not depend on which slot traced which path) and their count added to the accumulated
// image; after the frame's last batch, the average to the HDR target (alpha: whether the camera ray hit an object).
#include "common/frame.glsl"
#include "methods/random_walk/random_walk_io.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { RandomWalkGPU method; };
layout(std430, binding = LUCENT_BINDING_WALK_RESULTS) readonly buffer ResultBlock { vec4 results[]; };
layout(rgba32f, binding = LUCENT_IMAGE_WALK_SUM) uniform image2D accumulated;
layout(rgba32f, binding = LUCENT_IMAGE_HDR) uniform writeonly image2D hdr;
layout(std430, binding = LUCENT_BINDING_COUNTERS) buffer CounterBlock { CountersGPU counters; };
layout(std430, binding = LUCENT_BINDING_WALK_COUNTERS) buffer WalkCounterBlock { WalkCountersGPU walk_counters; };

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy), size = frame.output_size.xy;
  if (pixel.x >= size.x || pixel.y >= size.y) return;
  uint pixels = method.pool.w, pixel_index = uint((size.y - 1 - pixel.y) * size.x + pixel.x);
  uint batch_samples = method.pool.y / pixels, offset = method.pool.z * method.pool.y;
  bool first = (method.ring.y & LUCENT_WALK_POOL_FIRST) != 0u, last = (method.ring.y & LUCENT_WALK_POOL_LAST) != 0u;
  vec4 sum = first && frame.seeds.z != 0u ? vec4(0.0f) : imageLoad(accumulated, pixel);
  uint bits = 0u, steps = 0u, paths = 0u;
  // loop bound: param.samples_per_frame; a batch holds at most the frame's samples
  for (uint s = 0u; s < batch_samples; ++s) {
    vec4 r = results[offset + s * pixels + pixel_index];
    uint b = uint(r.a);
    bits |= b & 7u;
    if ((b & LUCENT_WALK_RESULT_COVERED) != 0u) steps += b >> 3u, ++paths;  // as volpath: pixels that hit something
    if ((b & LUCENT_WALK_RESULT_VALID) != 0u) sum += vec4(r.rgb, 1.0f);
  }
  uint low = atomicAdd(walk_counters.frame_steps.x, steps);
  if (low + steps < low) atomicAdd(walk_counters.frame_steps.y, 1u);
  atomicAdd(walk_counters.frame_paths, paths);
  imageStore(accumulated, pixel, sum);
  if (first && (bits & LUCENT_WALK_RESULT_TRANSLUCENT) != 0u) {
    atomicAdd(counters.translucent_pixels, 1u);
    atomicAdd(counters.covered_pixels, 1u);
  }
  if (last)
    imageStore(hdr, pixel, vec4(sum.rgb / max(sum.a, 1.0f), (bits & LUCENT_WALK_RESULT_COVERED) != 0u ? 1.0f : 0.0f));
}
