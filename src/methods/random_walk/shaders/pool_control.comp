// pool_control.comp: after each trace dispatch, the next one's work groups (read by glDispatchComputeIndirect),
// so that a frame advances without the host reading anything back: every slot's group until the current frame's
// paths have all finished (slots its paths no longer need start the next frames' paths), none after. Counts the
// dispatches with work and those with under a tenth of the slots busy (the tail, where the longest paths finish).
// A frame that lost a path (none in flight or left to start, some unfinished) gets no more work groups.
#include "common/frame.glsl"
#include "methods/random_walk/random_walk_io.h"

layout(local_size_x = 1, local_size_y = 1, local_size_z = 1) in;

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { RandomWalkGPU method; };
layout(std430, binding = LUCENT_BINDING_WALK_COUNTERS) buffer WalkCounterBlock { WalkCountersGPU walk_counters; };

void main() {
  uint slots = method.pool.x, busy = walk_counters.busy, current = method.pool.z, left = 0u;
  for (uint r = 0u; r < LUCENT_WALK_MAX_REGIONS && r < method.ring.x; ++r) {
    uint started = walk_counters.next_path[r];
    left += started < method.pool.y ? method.pool.y - started : 0u;
  }
  walk_counters.last_busy = busy;
  walk_counters.busy = 0u;
  uint finished = walk_counters.finished[current];
  // No slot holds a path and none is left to start, yet the frame has not finished them all: a path was lost, and
  // dispatching more would wait for it forever.
  walk_counters.lost = busy == 0u && left == 0u && finished < method.pool.y ? method.pool.y - finished : 0u;
  bool work = finished < method.pool.y && walk_counters.lost == 0u;
  walk_counters.groups = uvec4(work ? (slots + LUCENT_WALK_POOL_GROUP - 1u) / LUCENT_WALK_POOL_GROUP : 0u, 1u, 1u, 0u);
  uvec2 tiles = (uvec2(frame.output_size.xy) + 7u) / 8u;
  walk_counters.resolve_groups = work || walk_counters.lost != 0u ? uvec4(0u, 1u, 1u, 0u) : uvec4(tiles, 1u, 0u);
  if (!work) return;
  walk_counters.dispatches += 1u;
  if (10u * min(slots, busy + left) < slots) walk_counters.sparse_dispatches += 1u;
}
