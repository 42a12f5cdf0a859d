// shape_diameter.h: the local thickness of a closed mesh, as the shape diameter function measures it (Shapira,
// Shamir and Cohen-Or 2008, through CGAL's Surface_mesh_segmentation: a cone of rays into the mesh from each
// triangle, their lengths averaged after outliers are removed). Used for the multipole model's thickness
// (a material's `"thickness_from_mesh": true`: the part's thickness without measuring it by hand).
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "lucent/mesh.h"

namespace lucent {

// The median shape diameter of a slab of unit thickness (a 1 x 20 x 20 box, its rims a few per cent of its area):
// rays at theta from the inward normal cross it in 1 / cos(theta), so the diameter over-reads a slab's thickness by
// this factor; divided by it, a slab's diameter is its thickness (ShapeDiameter.MeasuresSlabsShellsAndSpheres
// checks the value for slabs and for a thin shell).
constexpr double kShapeDiameterOfUnitSlab = 1.245;

struct ShapeDiameter {
  std::vector<double> per_triangle;  // [mesh units]; negative where no ray met the mesh again (an open border)
  double median = 0.0;               // area-weighted median over the triangles with a value [mesh units]
  double measured_area_fraction = 0.0;  // the share of the area with a value
};

// `world_from_object` is applied first, so values are in the scene's units. The mesh should be closed and wound
// with outward normals (lucent's convention); rays leave each triangle's centroid inward, in a cone of 120 degrees,
// 25 rays per triangle (CGAL's defaults). Throws lucent::Error when no triangle has a value.
ShapeDiameter shape_diameter(const TriangleMesh& mesh, const glm::mat4& world_from_object);

}  // namespace lucent
