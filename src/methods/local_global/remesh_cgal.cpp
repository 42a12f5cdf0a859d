// remesh_cgal.cpp: see remesh.h. The only translation unit that includes CGAL.
#include "methods/local_global/remesh.h"

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Surface_mesh.h>
#include <fmt/format.h>

#include "geometry/position_bits.h"
#include "lucent/error.h"

namespace lucent::methods::local_global {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace

TriangleMesh remesh_isotropic(const TriangleMesh& mesh, const RemeshOptions& options) {
  if (!(options.target_edge > 0.0) || !std::isfinite(options.target_edge))
    throw Error(fmt::format("remeshing: target edge length {} is not positive", options.target_edge));

  // A polygon soup of the welded positions.
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  std::map<std::array<std::uint32_t, 3>, std::size_t> index_of;
  std::vector<std::size_t> welded(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const auto [it, added] = index_of.emplace(position_bits(mesh.positions[v]), points.size());
    if (added) points.emplace_back(mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z);
    welded[v] = it->second;
  }
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::size_t a = welded[mesh.indices[t]], b = welded[mesh.indices[t + 1]], c = welded[mesh.indices[t + 2]];
    if (a != b && b != c && a != c) polygons.push_back({a, b, c});
  }
  PMP::repair_polygon_soup(points, polygons);
  PMP::orient_polygon_soup(points, polygons);  // false: vertices were duplicated to make it manifold; still a surface
  SurfaceMesh surface;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, surface);
  if (surface.number_of_faces() == 0 || !CGAL::is_triangle_mesh(surface))
    throw Error("remeshing: the mesh has no orientable triangle surface");
  // Orientation: the input's faces are counter-clockwise seen from outside; keep that for closed surfaces.
  if (CGAL::is_closed(surface) && !PMP::is_outward_oriented(surface)) PMP::reverse_face_orientations(surface);

  // Sharp edges: split to the target length, then protected (neither collapsed, flipped nor moved).
  auto feature = surface.add_property_map<SurfaceMesh::Edge_index, bool>("e:lucent_feature", false).first;
  PMP::detect_sharp_edges(surface, options.feature_deg, feature);
  std::vector<SurfaceMesh::Edge_index> sharp;
  for (SurfaceMesh::Edge_index e : surface.edges())
    if (feature[e]) sharp.push_back(e);
  PMP::split_long_edges(sharp, options.target_edge, surface, CGAL::parameters::edge_is_constrained_map(feature));
  PMP::isotropic_remeshing(faces(surface), options.target_edge, surface,
                           CGAL::parameters::number_of_iterations(static_cast<unsigned>(options.iterations))
                               .edge_is_constrained_map(feature)
                               .protect_constraints(true));
  surface.collect_garbage();

  // Per-corner normals: the area-weighted face normals around the corner's vertex within feature_deg of the
  // corner's own face (a vertex on a sharp edge gets one copy per side).
  const std::size_t vertex_count = surface.number_of_vertices();
  std::vector<glm::dvec3> position(vertex_count);
  for (SurfaceMesh::Vertex_index v : surface.vertices()) {
    const Point& p = surface.point(v);
    position[v.idx()] = glm::dvec3(p.x(), p.y(), p.z());
  }
  std::vector<std::array<std::size_t, 3>> triangles;
  for (SurfaceMesh::Face_index f : surface.faces()) {
    std::array<std::size_t, 3> tri{};
    int k = 0;
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(surface.halfedge(f), surface)) tri[static_cast<std::size_t>(k++ % 3)] = v.idx();
    if (k == 3) triangles.push_back(tri);
  }
  std::vector<glm::dvec3> face_normal(triangles.size());  // length: twice the area
  std::vector<std::vector<std::size_t>> faces_of(vertex_count);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& [a, b, c] = triangles[t];
    face_normal[t] = glm::cross(position[b] - position[a], position[c] - position[a]);
    for (std::size_t v : triangles[t]) faces_of[v].push_back(t);
  }
  const double cos_feature = std::cos(options.feature_deg * 3.14159265358979323846 / 180.0);
  TriangleMesh out;
  std::map<std::pair<std::size_t, std::array<std::uint32_t, 3>>, std::uint32_t> corner_index;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const double own_length = glm::length(face_normal[t]);
    for (std::size_t v : triangles[t]) {
      glm::dvec3 n(0.0);
      for (std::size_t g : faces_of[v]) {
        const double length = glm::length(face_normal[g]);
        if (own_length <= 0.0 || length <= 0.0 || glm::dot(face_normal[t], face_normal[g]) >= cos_feature * own_length * length)
          n += face_normal[g];
      }
      if (!(glm::length(n) > 0.0)) n = face_normal[t];
      const glm::vec3 unit = glm::length(n) > 0.0 ? glm::vec3(glm::normalize(n)) : glm::vec3(0.0f, 0.0f, 1.0f);
      const auto [it, added] = corner_index.emplace(std::make_pair(v, position_bits(unit)),
                                                    static_cast<std::uint32_t>(out.positions.size()));
      if (added) {
        out.positions.push_back(glm::vec3(position[v]));
        out.normals.push_back(unit);
      }
      out.indices.push_back(it->second);
    }
  }
  if (out.indices.empty()) throw Error("remeshing: no triangle left");
  return out;
}

}  // namespace lucent::methods::local_global
