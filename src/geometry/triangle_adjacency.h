// triangle_adjacency.h: each triangle's neighbour across each of its edges, for walking on a mesh's surface (the
// specular-chain solvers step across edges: shared/specular_chain.h). Edges are matched by their corners' positions,
// not their vertex indices, so a mesh whose vertices are split along a texture seam or a normal crease still walks
// across it.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

// neighbours[t][k]: the triangle across edge k of triangle t (edge 0 joins corners 0 and 1, edge 1 corners 1 and 2,
// edge 2 corners 2 and 0), or -1 on the mesh's border and where more than two triangles share the edge.
std::vector<std::array<std::int32_t, 3>> triangle_neighbours(std::span<const glm::vec3> positions,
                                                             std::span<const std::uint32_t> indices);

}  // namespace lucent
