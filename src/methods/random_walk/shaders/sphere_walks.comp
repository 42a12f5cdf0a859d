// sphere_walks.comp: the frame's sphere-jump records: for every bank (a medium's Henyey-Greenstein g), level
// (optical radius 2^(l+1)) and record, one canonical walk from the sphere's centre to its surface
// (shared/sphere_walk.h, the function the CPU reference's banks come from), seeded by the first sample index of the
// frame whose paths read them, so every frame draws fresh, independent records (docs/methods/random-walk.md,
// "Sphere jumps"). One set per results region (the frames in flight); the dispatch's z runs over every region's
// banks and fills those of the ring.w regions from ring.z on.
#include "common/frame.glsl"
#include "shared/sphere_walk.h"
#include "methods/random_walk/random_walk_io.h"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { RandomWalkGPU method; };
layout(std430, binding = LUCENT_BINDING_WALK_SPHERES) writeonly buffer SphereBlock { SphereWalkGPU spheres[]; };

void main() {
  int banks = method.jump_info.x, record = int(gl_GlobalInvocationID.x), level = int(gl_GlobalInvocationID.y);
  int region = int(gl_GlobalInvocationID.z) / banks, bank = int(gl_GlobalInvocationID.z) % banks;
  uint after = (uint(region) + method.ring.x - method.ring.z) % method.ring.x;  // regions after the first one made
  if (record >= method.jump_records[level / 4][level % 4] || after >= method.ring.w) return;
  uint first_sample = method.region_first[region / 4][region % 4];
  uint seed = seed_from(method.samples.z, first_sample, uint(level) << 24u ^ uint(bank), uint(record));
  if (frame.seeds.w != 0u) seed = seed_from(seed, frame.seeds.w, 0x5eed64u, 0u);  // the seed's high 32 bits
  int index = ((region * banks + bank) * kSphereJumpLevelCount + level) * method.distance_size.w + record;
  spheres[index] = sphere_walk(sphere_jump_level_radius(level), method.jump_g[bank], seed);
}
