// sphere_walks.comp: the frame's sphere-jump records: for every bank (a medium's Henyey-Greenstein g), level
// (optical radius 2^(l+1)) and record, one canonical walk from the sphere's centre to its surface
// (shared/sphere_walk.h, the function the CPU reference's banks come from), seeded by the frame's first sample
// index, so every frame draws fresh, independent records (docs/methods/random-walk.md, "Sphere jumps").
#include "common/frame.glsl"
#include "shared/sphere_walk.h"
#include "methods/random_walk/random_walk_io.h"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { RandomWalkGPU method; };
layout(std430, binding = LUCENT_BINDING_WALK_SPHERES) writeonly buffer SphereBlock { SphereWalkGPU spheres[]; };

void main() {
  int record = int(gl_GlobalInvocationID.x), level = int(gl_GlobalInvocationID.y), bank = int(gl_GlobalInvocationID.z);
  if (record >= method.jump_records[level / 4][level % 4]) return;
  uint seed = seed_from(method.samples.z, method.samples.y, uint(level) << 24u ^ uint(bank), uint(record));
  int index = (bank * kSphereJumpLevelCount + level) * method.distance_size.w + record;
  spheres[index] = sphere_walk(sphere_jump_level_radius(level), method.jump_g[bank], seed);
}
