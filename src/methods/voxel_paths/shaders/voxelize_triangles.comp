// voxelize_triangles.comp: solid voxelization by parity, step 1 of 2 (voxel-paths, paper Section 2.1 "solid
// voxelization"). One invocation per triangle of one object and row slice, read in place from the scene's vertex and index
// buffers (so deforming objects voxelize as they are this frame): for every voxel column (x, y) whose centre its
// xy projection covers, the crossing of the column's +z ray toggles the flip bit of the first voxel whose centre
// lies above the crossing. voxelize_scan.comp then XOR-accumulates the flips up each column: a voxel is inside
// when an odd number of surfaces lie below its centre. Watertight: the edge function of a shared edge is
// computed from the same endpoint by both triangles and ties go to one of them (top-left style rule), so a
// column through an edge toggles once.
layout(local_size_x = 64) in;

#include "shared/shader_io.h"

layout(std430, binding = VOXEL_BINDING_TRIANGLES) readonly buffer VertexBlock { VertexGPU vertices[]; };
layout(std430, binding = VOXEL_BINDING_INDICES) readonly buffer IndexBlock { uint indices[]; };
layout(std430, binding = VOXEL_BINDING_FLIPS) buffer FlipBlock { uint flips[]; };

uniform uint u_first_index;  // the object's first triangle corner in indices[]
uniform uint u_triangle_count;
uniform vec3 u_origin;      // corner of voxel (0, 0, 0) [scene units]
uniform float u_voxel_size;  // h [scene units]
uniform int u_resolution;    // R

// Edge function of p against the directed edge a -> b (positive to its left), evaluated from the
// lexicographically smaller endpoint so that a -> b and b -> a give exactly opposite values.
float edge_function(vec2 a, vec2 b, vec2 p) {
  bool swapped = a.x > b.x || (a.x == b.x && a.y > b.y);
  vec2 s = swapped ? b : a, t = swapped ? a : b;
  float e = (t.x - s.x) * (p.y - s.y) - (t.y - s.y) * (p.x - s.x);
  return swapped ? -e : e;
}

// Inside test of one edge of a counter-clockwise triangle; points on the edge belong to exactly one of the
// two triangles that traverse it in opposite directions.
bool inside_edge(float e, vec2 a, vec2 b) {
  if (e != 0.0f) return e > 0.0f;
  vec2 d = b - a;
  return d.y < 0.0f || (d.y == 0.0f && d.x > 0.0f);
}

void main() {
  if (gl_GlobalInvocationID.x >= u_triangle_count) return;
  uint t = u_first_index + 3u * gl_GlobalInvocationID.x;
  vec3 a = vertices[indices[t]].position.xyz, b = vertices[indices[t + 1u]].position.xyz;
  vec3 c = vertices[indices[t + 2u]].position.xyz;
  // Counter-clockwise in xy; triangles seen edge-on from the column direction cross no column.
  float area2 = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (area2 == 0.0f) return;
  if (area2 < 0.0f) {
    vec3 s = b;
    b = c, c = s;
  }
  // Columns whose centres lie in the triangle's xy bounding box.
  vec2 lower = (min(a.xy, min(b.xy, c.xy)) - u_origin.xy) / u_voxel_size - 0.5f;
  vec2 upper = (max(a.xy, max(b.xy, c.xy)) - u_origin.xy) / u_voxel_size - 0.5f;
  ivec2 first = max(ivec2(ceil(lower)), ivec2(0));
  ivec2 last = min(ivec2(floor(upper)), ivec2(u_resolution - 1));
  // Rows interleaved over the dispatch's gl_NumWorkGroups.y slices (voxelizer.cpp dispatches 4), so that a
  // triangle covering the whole grid runs at most 64 x 256 iterations per invocation, under llvmpipe's loop cap.
  int slices = int(gl_NumWorkGroups.y);
  // loop bound: 64 x 256; resolution <= 256 rows over 4 slices (voxelizer.cpp), resolution <= 256 columns each
  for (int j = first.y + int(gl_GlobalInvocationID.y); j <= last.y; j += slices)
    // loop bound: 64 x 256; the columns of one row, resolution <= 256, counted with the loop above
    for (int i = first.x; i <= last.x; ++i) {
      vec2 p = u_origin.xy + (vec2(i, j) + 0.5f) * u_voxel_size;
      float e_a = edge_function(b.xy, c.xy, p), e_b = edge_function(c.xy, a.xy, p), e_c = edge_function(a.xy, b.xy, p);
      if (!inside_edge(e_a, b.xy, c.xy) || !inside_edge(e_b, c.xy, a.xy) || !inside_edge(e_c, a.xy, b.xy)) continue;
      float sum = e_a + e_b + e_c;
      if (sum <= 0.0f) continue;
      float z = (e_a * a.z + e_b * b.z + e_c * c.z) / sum;
      int k = int(floor((z - u_origin.z) / u_voxel_size - 0.5f)) + 1;
      k = max(k, 0);
      if (k >= u_resolution) continue;
      atomicXor(flips[(uint(k) * uint(u_resolution) + uint(j)) * uint(u_resolution) + uint(i)], 1u);
    }
}
