// isosurface_cpu.cpp: marching tetrahedra on the CPU, in the GPU's order (see isosurface_cpu.h).
#include "geometry/isosurface_cpu.h"

#include <cstdint>

#include "geometry/marching_tetrahedra.h"

namespace lucent::geometry {
namespace {

using namespace lucent::shader;

// The shader's vertex normal: the outward gradient direction, or the edge direction (inside to outside)
// where the gradient vanishes.
glm::vec3 vertex_normal(const BlobState& field, glm::vec3 position, glm::vec3 edge_inside_to_outside) {
  glm::vec3 outward = -blob_field_gradient_of(field, position);
  if (glm::dot(outward, outward) < 1e-20f) outward = edge_inside_to_outside;
  return glm::normalize(outward);
}

}  // namespace

std::vector<float> sample_blob_field(const IsosurfaceGrid& grid, float time_seconds) {
  std::vector<float> samples(grid.point_count());
  glm::ivec3 n = grid.points();
  glm::vec3 spacing = grid.spacing();
  BlobState field = blob_state(time_seconds);
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        glm::ivec3 p(x, y, z);
        float f = blob_field_of(field, mt_grid_position(grid.lower, spacing, p));
        samples[grid.point_index(p)] = mt_stored_sample(f, p, grid.cells);
      }
  return samples;
}

TriangleMesh extract_blob_isosurface(const IsosurfaceGrid& grid, const std::vector<float>& samples,
                                     float time_seconds) {
  glm::ivec3 n = grid.points();
  glm::vec3 spacing = grid.spacing();
  BlobState field = blob_state(time_seconds);
  auto sample = [&](glm::ivec3 p) { return samples[grid.point_index(p)]; };
  auto in_grid = [&](glm::ivec3 p) { return p.x < n.x && p.y < n.y && p.z < n.z; };

  // Step 1: crossing edges of each point and the index of its first vertex (a serial exclusive scan).
  std::vector<std::uint32_t> edge_masks(grid.point_count()), first_vertex(grid.point_count());
  std::uint32_t vertex_count = 0;
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        glm::ivec3 p(x, y, z);
        std::uint32_t mask = 0;
        for (int direction = 1; direction <= LUCENT_MT_DIRECTIONS; ++direction) {
          glm::ivec3 q = p + mt_corner_offset(direction);
          if (in_grid(q)) mask |= mt_edge_bit(p, grid.cells, direction, sample(p), sample(q));
        }
        std::size_t i = grid.point_index(p);
        edge_masks[i] = mask;
        first_vertex[i] = vertex_count;
        vertex_count += static_cast<std::uint32_t>(glm::bitCount(mask));
      }

  // Step 2: vertices, point by point, direction by direction.
  TriangleMesh mesh;
  mesh.positions.reserve(vertex_count);
  mesh.normals.reserve(vertex_count);
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        glm::ivec3 p(x, y, z);
        std::uint32_t mask = edge_masks[grid.point_index(p)];
        for (int direction = 1; direction <= LUCENT_MT_DIRECTIONS; ++direction) {
          if ((mask & (1u << (direction - 1))) == 0) continue;
          glm::ivec3 q = p + mt_corner_offset(direction);
          float f_p = sample(p), f_q = sample(q);
          glm::vec3 a = mt_grid_position(grid.lower, spacing, p), b = mt_grid_position(grid.lower, spacing, q);
          glm::vec3 position = a + mt_edge_fraction(f_p, f_q) * (b - a);
          mesh.positions.push_back(position);
          mesh.normals.push_back(vertex_normal(field, position, mt_inside(f_p) ? b - a : a - b));
        }
      }

  // Step 3: triangles, cell by cell, tetrahedron by tetrahedron.
  for (int z = 0; z < grid.cells.z; ++z)
    for (int y = 0; y < grid.cells.y; ++y)
      for (int x = 0; x < grid.cells.x; ++x) {
        glm::ivec3 cell(x, y, z);
        int cube_inside = 0;
        for (int c = 0; c < 8; ++c)
          if (mt_inside(sample(cell + mt_corner_offset(c)))) cube_inside |= 1 << c;
        for (int tet = 0; tet < LUCENT_MT_TETS_PER_CELL; ++tet) {
          int inside = mt_tet_inside_mask(tet, cube_inside);
          for (int t = 0; t < mt_tet_triangle_count(inside); ++t) {
            glm::ivec3 edges = mt_tet_triangle(inside, mt_tet_parity(tet), t);
            for (int v = 0; v < 3; ++v) {
              int lower = mt_tet_corner(tet, edges[v] / 4), upper = mt_tet_corner(tet, edges[v] % 4);
              std::size_t owner = grid.point_index(cell + mt_corner_offset(lower));
              mesh.indices.push_back(first_vertex[owner] + mt_vertex_rank(edge_masks[owner], upper - lower));
            }
          }
        }
      }
  return mesh;
}

TriangleMesh extract_blob_isosurface(const IsosurfaceGrid& grid, float time_seconds) {
  return extract_blob_isosurface(grid, sample_blob_field(grid, time_seconds), time_seconds);
}

}  // namespace lucent::geometry
