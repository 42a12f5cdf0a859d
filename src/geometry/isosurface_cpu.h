// isosurface_cpu.h: the CPU reference of the GPU blob isosurface extractor (geometry/blob_isosurface.h):
// the same marching tetrahedra (geometry/marching_tetrahedra.h) and field (geometry/blob_field.h), with the
// vertices and triangles in the same order: vertices by grid point, then edge direction; triangles by cell,
// then tetrahedron.
#pragma once
#include <vector>

#include "geometry/isosurface_grid.h"
#include "lucent/mesh.h"

namespace lucent::geometry {

// The stored sample of every grid point (index IsosurfaceGrid::point_index) at `time_seconds`: the field,
// with the box's outer points forced outside.
std::vector<float> sample_blob_field(const IsosurfaceGrid& grid, float time_seconds);

// The surface of the given samples; normals are the blob field's outward gradient normals at
// `time_seconds`. Positions in world space [scene units], counter-clockwise seen from outside.
TriangleMesh extract_blob_isosurface(const IsosurfaceGrid& grid, const std::vector<float>& samples,
                                     float time_seconds);
TriangleMesh extract_blob_isosurface(const IsosurfaceGrid& grid, float time_seconds);

}  // namespace lucent::geometry
