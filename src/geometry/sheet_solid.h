// sheet_solid.h: a surface given as a sheet (glTF's thin-walled materials: a leaf, a lampshade, a balloon's skin)
// made into the closed solid lucent's media need: the surface, a copy of it offset inward by the sheet's thickness
// with its winding reversed, and walls joining the two along the surface's open borders. A closed surface becomes a
// hollow shell of that wall thickness; an open one a closed slab.
#pragma once
#include "lucent/mesh.h"

namespace lucent {

// `thickness` in the mesh's units (> 0). The offset follows each position's normal (the area-weighted normals of
// the triangles that meet there, from their winding: the front is the side they face), so the back face lies
// `thickness` behind the front along it; creases and thicknesses beyond the surface's radius of curvature can fold
// the back face (not checked). Texture coordinates, where the mesh has them, are copied to the back face and the
// walls. Throws lucent::Error when the mesh has no triangle with an area or `thickness` is not positive and finite.
TriangleMesh sheet_solid(const TriangleMesh& mesh, float thickness);

}  // namespace lucent
