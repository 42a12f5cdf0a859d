// voxelize_scan.comp: solid voxelization by parity, step 2 of 2 (see voxelize_triangles.comp). One invocation
// per voxel column: XOR-accumulates the flips from z = 0 upward and labels the voxels with odd parity.
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = VOXEL_BINDING_FLIPS) readonly buffer FlipBlock { uint flips[]; };
layout(std430, binding = VOXEL_BINDING_LABELS) buffer LabelBlock { uint labels[]; };

uniform int u_resolution;  // R
uniform uint u_label;      // object index + 1

void main() {
  ivec2 column = ivec2(gl_GlobalInvocationID.xy);
  if (column.x >= u_resolution || column.y >= u_resolution) return;
  uint r = uint(u_resolution), parity = 0u;
  // loop bound: param.resolution; one column of the grid, resolution <= 256
  for (uint k = 0u; k < r; ++k) {
    uint index = (k * r + uint(column.y)) * r + uint(column.x);
    parity ^= flips[index];
    if (parity != 0u) labels[index] = u_label;
  }
}
