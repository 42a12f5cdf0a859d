// grid.glsl: the voxel grid of voxel-paths (methods/voxel_paths/voxel_grid.h): uniforms and indexing, x fastest.
uniform vec3 u_origin;       // corner of voxel (0, 0, 0) [scene units]
uniform float u_voxel_size;  // h [scene units]
uniform int u_resolution;    // R

bool in_grid(ivec3 v) { return all(greaterThanEqual(v, ivec3(0))) && all(lessThan(v, ivec3(u_resolution))); }
int voxel_index(ivec3 v) { return (v.z * u_resolution + v.y) * u_resolution + v.x; }
ivec3 voxel_of(vec3 x) { return ivec3(floor((x - u_origin) / u_voxel_size)); }
vec3 voxel_center(ivec3 v) { return u_origin + (vec3(v) + 0.5f) * u_voxel_size; }
