// blob_sample.comp: the blob field at every grid point, stored with the box's outer points forced outside.
#include "geometry/isosurface_grid.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std430, binding = LUCENT_BINDING_ISO_SAMPLES) writeonly buffer Samples { float samples[]; };

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (!is_grid_point(p)) return;
  samples[point_index(p)] = mt_stored_sample(blob_field_of(params.field, grid_position(p)), p, grid_cells());
}
