// remesh.h: isotropic remeshing of a triangle mesh to round triangles of one edge length (Lensch et al. 2002,
// Section 5.1: "round triangles of similar size"), through CGAL's Polygon Mesh Processing. The one file that
// includes CGAL is remesh_cgal.cpp (its compile time stays out of every other file); this header names no CGAL type.
#pragma once
#include "lucent/mesh.h"

namespace lucent::methods::local_global {

struct RemeshOptions {
  double target_edge = 0.0;   // edge length of the result [units of the mesh's positions]
  double feature_deg = 60.0;  // edges whose faces' normals differ by more are sharp: kept (split, never moved off)
  int iterations = 5;         // split / collapse / flip / smooth / project rounds (3 left 10% of a box's edges
                              // outside [0.6, 1.4] x the target, 5 7%)
};

// Vertices with equal positions are merged, the triangles stitched into one surface; sharp edges (feature_deg)
// are split to the target length and then protected, so corners and creases stay where they were. The result has
// per-corner normals from its faces (vertices split where faces meet at a sharp edge, smooth elsewhere) and no
// texture coordinates. Throws lucent::Error("remeshing: ...") when the input is not an orientable surface that
// CGAL can remesh.
TriangleMesh remesh_isotropic(const TriangleMesh& mesh, const RemeshOptions& options);

}  // namespace lucent::methods::local_global
