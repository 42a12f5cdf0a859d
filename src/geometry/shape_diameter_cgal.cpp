// shape_diameter_cgal.cpp: see shape_diameter.h. CGAL's headers are included here only (lucent_cgal).
#include "geometry/shape_diameter.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/mesh_segmentation.h>
#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;

constexpr double kConeAngle = 2.0 * CGAL_PI / 3.0;  // CGAL's default cone
constexpr std::size_t kRays = 25;                  // CGAL's default ray count

}  // namespace

ShapeDiameter shape_diameter(const TriangleMesh& mesh, const glm::mat4& world_from_object) {
  // Every triangle a face of its own (three fresh vertices): the rays need only the triangles and their winding,
  // and a soup keeps non-manifold or duplicated vertices of loaded meshes from refusing a face.
  SurfaceMesh surface;
  std::vector<SurfaceMesh::Face_index> faces;
  std::vector<double> areas;
  const std::size_t triangles = mesh.indices.size() / 3;
  faces.reserve(triangles);
  areas.reserve(triangles);
  std::vector<std::size_t> kept;  // triangle index of each face
  for (std::size_t t = 0; t < triangles; ++t) {
    std::array<glm::dvec3, 3> p{};
    std::array<SurfaceMesh::Vertex_index, 3> v{};
    for (int k = 0; k < 3; ++k) {
      const glm::vec4 world = world_from_object * glm::vec4(mesh.positions[mesh.indices[3 * t + static_cast<std::size_t>(k)]], 1.0f);
      p[static_cast<std::size_t>(k)] = glm::dvec3(world);
    }
    const double area = 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
    if (!(area > 0.0)) continue;  // degenerate: no normal, no rays
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3& q = p[static_cast<std::size_t>(k)];
      v[static_cast<std::size_t>(k)] = surface.add_vertex(Point(q.x, q.y, q.z));
    }
    const SurfaceMesh::Face_index f = surface.add_face(v[0], v[1], v[2]);
    if (f == SurfaceMesh::null_face()) continue;
    faces.push_back(f);
    areas.push_back(area);
    kept.push_back(t);
  }
  if (faces.empty()) throw Error("shape diameter: the mesh has no triangle with an area");

  auto sdf = surface.add_property_map<SurfaceMesh::Face_index, double>("f:sdf", -1.0).first;
  CGAL::sdf_values(surface, sdf, kConeAngle, kRays, /*postprocess=*/false);

  ShapeDiameter out;
  out.per_triangle.assign(triangles, -1.0);
  std::vector<std::pair<double, double>> measured;  // (value, area)
  double total_area = 0.0, measured_area = 0.0;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const double value = sdf[faces[i]];
    total_area += areas[i];
    if (!(value > 0.0) || !std::isfinite(value)) continue;
    out.per_triangle[kept[i]] = value;
    measured.emplace_back(value, areas[i]);
    measured_area += areas[i];
  }
  if (measured.empty())
    throw Error("shape diameter: no ray from the mesh met it again (an open surface, or normals that point inward)");
  std::sort(measured.begin(), measured.end());
  double below = 0.0;
  for (const auto& [value, area] : measured) {
    below += area;
    if (below >= 0.5 * measured_area) {
      out.median = value;
      break;
    }
  }
  out.measured_area_fraction = measured_area / total_area;
  return out;
}

}  // namespace lucent
