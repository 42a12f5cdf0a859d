// mesh_enclosure.h: whether a triangle mesh bounds a volume, and which points it encloses. A translucent object
// is a medium only inside a closed surface, and a point light inside one reaches no surface from outside.
#pragma once
#include <cstddef>

#include <glm/glm.hpp>

#include "lucent/mesh.h"

namespace lucent {

// Edges used by exactly one triangle, edges matched by their end positions (so seams with split vertices still
// close the surface); degenerate edges (both ends at one position) are not counted. 0 for a closed surface.
std::size_t open_edge_count(const TriangleMesh& mesh);

// Whether `p` lies inside the closed surface `mesh` (both in the same space): the parity of the mesh's crossings
// along a fixed ray from p, in double precision. Meaningless for an open surface.
bool encloses(const TriangleMesh& mesh, const glm::dvec3& p);

}  // namespace lucent
