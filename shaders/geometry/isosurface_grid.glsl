// isosurface_grid.glsl: the extraction's parameters and grid-point indexing, shared by the isosurface passes.
#include "geometry/isosurface_io.h"
#include "geometry/marching_tetrahedra.h"

layout(std140, binding = LUCENT_BINDING_ISO_PARAMS) uniform IsosurfaceParams { IsosurfaceParamsGPU params; };

ivec3 grid_cells() { return params.cells.xyz; }

// Linear index of a grid point (points 0..cells per axis), x fastest; the same as IsosurfaceGrid::point_index.
uint point_index(ivec3 p) {
  ivec3 n = params.cells.xyz + 1;
  return uint(p.x) + uint(n.x) * (uint(p.y) + uint(n.y) * uint(p.z));
}

ivec3 point_from_index(uint i) {
  uvec3 n = uvec3(params.cells.xyz + 1);
  return ivec3(uvec3(i % n.x, (i / n.x) % n.y, i / (n.x * n.y)));
}

bool is_grid_point(ivec3 p) { return all(lessThanEqual(p, params.cells.xyz)); }

vec3 grid_position(ivec3 p) { return mt_grid_position(params.lower.xyz, params.spacing.xyz, p); }
