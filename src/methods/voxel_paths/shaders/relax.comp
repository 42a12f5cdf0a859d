// relax.comp: one sweep of parallel Bellman-Ford relaxation of the shortest optical paths n(v) over the inside
// voxels (voxel-paths; the paper solves the same graph with Dijkstra's algorithm, Section 2.1). Every inside
// voxel takes, per colour band, the minimum over its 26 inside neighbours u of n(u) + cost(u, v), with
// cost = sigma_t integrated along the edge by the trapezoid rule: 0.5 (sigma_t(u) + sigma_t(v)) |u - v|, with
// sigma_t per voxel (fill_coefficients.comp: the material times the heterogeneous field).
// Updates are in place: values only decrease and each 32-bit store is atomic, so a sweep that reads a
// neighbour's newer value converges no slower. Any lowered value sets `changed`.
// With VOXEL_ACTIVE_BLOCKS (the "blocks" solver): a workgroup is a 4^3 block of voxels, and it runs only if its
// own block or one of its 26 neighbour blocks lowered a value in the previous sweep (`active_in`; all blocks in
// the first sweep). A voxel can only improve after a neighbour improved, and neighbours lie in those 27 blocks,
// so skipping the others changes nothing but the work: the same fixed point, far fewer voxel visits.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(std430, binding = VOXEL_BINDING_LABELS) readonly buffer LabelBlock { uint labels[]; };
layout(std430, binding = VOXEL_BINDING_SIGMA_T) readonly buffer SigmaTBlock { vec4 sigma_t[]; };  // per voxel
layout(std430, binding = VOXEL_BINDING_DISTANCES) coherent buffer DistanceBlock { vec4 distances[]; };
layout(std430, binding = VOXEL_BINDING_CHANGED) buffer ChangedBlock { uint changed; };

uniform int u_resolution;    // R
uniform float u_voxel_size;  // h [scene units]

#ifdef VOXEL_ACTIVE_BLOCKS
layout(std430, binding = VOXEL_BINDING_BLOCKS_IN) readonly buffer BlocksIn { uint active_in[]; };
layout(std430, binding = VOXEL_BINDING_BLOCKS_OUT) writeonly buffer BlocksOut { uint changed_out[]; };
shared bool s_active;

int block_index(ivec3 b) {
  ivec3 count = ivec3(gl_NumWorkGroups);
  return (b.z * count.y + b.y) * count.x + b.x;
}
#endif

void main() {
#ifdef VOXEL_ACTIVE_BLOCKS
  if (gl_LocalInvocationIndex == 0u) {
    ivec3 b = ivec3(gl_WorkGroupID), count = ivec3(gl_NumWorkGroups);
    bool any_changed = false;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          ivec3 c = b + ivec3(dx, dy, dz);
          if (all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, count)) && active_in[block_index(c)] != 0u)
            any_changed = true;
        }
    s_active = any_changed;
  }
  barrier();
  if (!s_active) return;
#endif
  ivec3 v = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(v, ivec3(u_resolution)))) return;
  int r = u_resolution;
  int index = (v.z * r + v.y) * r + v.x;
  uint label = labels[index];
  if (label == 0u) return;
  vec3 sigma_v = sigma_t[index].rgb;
  vec3 n = distances[index].rgb;
  vec3 best = n;
  const float kLength[4] = float[4](0.0f, 1.0f, 1.4142135f, 1.7320508f);  // = kEdgeLength (voxel_dijkstra.h)
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 u = v + ivec3(dx, dy, dz);
        if (any(lessThan(u, ivec3(0))) || any(greaterThanEqual(u, ivec3(r)))) continue;
        int neighbour = (u.z * r + u.y) * r + u.x;
        uint label_u = labels[neighbour];
        if (label_u == 0u || neighbour == index) continue;
        float edge = u_voxel_size * kLength[abs(dx) + abs(dy) + abs(dz)];
        best = min(best, distances[neighbour].rgb + 0.5f * (sigma_v + sigma_t[neighbour].rgb) * edge);
      }
  if (any(lessThan(best, n))) {
    distances[index] = vec4(best, 0.0f);
    changed = 1u;
#ifdef VOXEL_ACTIVE_BLOCKS
    changed_out[block_index(ivec3(gl_WorkGroupID))] = 1u;
#endif
  }
}
