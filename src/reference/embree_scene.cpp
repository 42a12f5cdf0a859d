// embree_scene.cpp: see embree_scene.h.
#include "reference/embree_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "geometry/closest_point.h"
#include "geometry/thickness_grid.h"
#include "geometry/triangle_adjacency.h"
#include "lucent/error.h"
#include "scene/mesh_enclosure.h"

namespace lucent::reference {
namespace {

template <typename Vec>
double largest_abs(const Vec& v) {
  return std::max({std::abs(static_cast<double>(v.x)), std::abs(static_cast<double>(v.y)),
                   std::abs(static_cast<double>(v.z))});
}

ObjectData object_data(const SceneObject& object, float scale_mm) {
  ObjectData d;
  TriangleMesh world = transformed(object.mesh, object.world_from_object);
  d.positions = std::move(world.positions);
  d.normals = std::move(world.normals);
  d.indices = std::move(world.indices);
  double total = 0.0;
  std::vector<double> areas;
  for (std::size_t t = 0; t + 2 < d.indices.size(); t += 3) {
    ObjectData::Corners c;
    c.magnitude = 0.0f;
    for (std::size_t k = 0; k < 3; ++k) {
      c.position[k] = d.positions[d.indices[t + k]], c.normal[k] = d.normals[d.indices[t + k]];
      c.magnitude = std::max(c.magnitude, static_cast<float>(largest_abs(c.position[k])));
    }
    glm::dvec3 a = c.position[0], b = c.position[1], e = c.position[2];
    areas.push_back(0.5 * glm::length(glm::cross(b - a, e - a)));
    total += areas.back();
    d.corners.push_back(c);
  }
  if (total > 0.0) d.triangle_by_area = AliasTable(areas);  // else never sampled: nothing can hit it either
  d.area = total;
  d.albedo = object.albedo;
  if (object.material) {
    const Material& m = *object.material;
    d.translucent = true;
    d.neighbours = triangle_neighbours(d.positions, d.indices);
    d.planes.reserve(d.corners.size());
    for (const ObjectData::Corners& c : d.corners) {
      const glm::dvec3 a(c.position[0]), b(c.position[1]), e(c.position[2]);
      const glm::dvec3 cross = glm::cross(b - a, e - a);
      const double length = glm::length(cross);
      glm::dvec3 n = length > 0.0 ? cross / length : glm::dvec3(0.0);
      if (glm::dot(n, glm::dvec3(c.normal[0] + c.normal[1] + c.normal[2])) < 0.0) n = -n;
      d.planes.emplace_back(glm::vec3(n), static_cast<float>(std::sqrt(0.5 * length)));
    }
    d.faces = flat_patches(d.positions, d.indices, d.normals, d.neighbours);
    d.sigma_a = glm::dvec3(m.sigma_a) * static_cast<double>(scale_mm);
    d.sigma_s = glm::dvec3(m.sigma_s) * static_cast<double>(scale_mm);
    d.g = m.g;
    d.eta = m.eta;
    d.model = static_cast<int>(m.model);
    d.thickness = static_cast<double>(m.thickness_mm) / static_cast<double>(scale_mm);
    d.thickness_grid = object.thickness;
    d.field = m.field;
    d.scale_mm = scale_mm;
    d.lower = glm::vec3(std::numeric_limits<float>::max()), d.upper = -d.lower;
    for (const glm::vec3& p : d.positions) d.lower = glm::min(d.lower, p), d.upper = glm::max(d.upper, p);
    d.mesh_lower = d.lower, d.mesh_upper = d.upper;
    if (m.field.has_bounds) d.lower = m.field.bounds_lower, d.upper = m.field.bounds_upper;
    d.majorant = static_cast<double>(m.field.max_multiplier()) * (d.sigma_a + d.sigma_s);
    if (m.maps) {  // check_material_maps: the mesh has texture coordinates
      d.maps = m.maps;
      d.corner_uvs.reserve(d.corners.size());
      for (std::size_t t = 0; t + 2 < d.indices.size(); t += 3)
        d.corner_uvs.push_back({object.mesh.uvs[d.indices[t]], object.mesh.uvs[d.indices[t + 1]],
                                object.mesh.uvs[d.indices[t + 2]]});
    }
  }
  return d;
}

glm::dvec2 corner_uv(const ObjectData& d, unsigned triangle, double b1, double b2) {
  if (!d.textured()) return glm::dvec2(0.0);
  const std::array<glm::vec2, 3>& uv = d.corner_uvs[triangle];
  return (1.0 - b1 - b2) * glm::dvec2(uv[0]) + b1 * glm::dvec2(uv[1]) + b2 * glm::dvec2(uv[2]);
}

}  // namespace

double ObjectData::thickness_at(const glm::dvec3& x) const {
  return thickness_grid.empty() ? thickness : static_cast<double>(lucent::thickness_at(thickness_grid, glm::vec3(x)));
}

MediumCoefficients ObjectData::medium_at(glm::dvec2 uv) const {
  if (!maps) return {sigma_a, sigma_s};
  glm::vec3 a, s;
  maps->coefficients(glm::vec2(uv), a, s);
  return {glm::dvec3(a) * static_cast<double>(scale_mm), glm::dvec3(s) * static_cast<double>(scale_mm)};
}

EmbreeScene::EmbreeScene(const Scene& scene) {
  check_material_maps(scene);
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw Error("Embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  for (const SceneObject& object : scene.objects) {
    objects_.push_back(object_data(object, scene.scale_mm));
    const ObjectData& d = objects_.back();
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), d.positions.size()));
    for (std::size_t i = 0; i < d.positions.size(); ++i)
      for (int k = 0; k < 3; ++k) vertices[3 * i + static_cast<std::size_t>(k)] = d.positions[i][k];
    auto* indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), d.indices.size() / 3));
    std::copy(d.indices.begin(), d.indices.end(), indices);
    rtcCommitGeometry(geometry);
    unsigned id = rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    if (object_of_geometry_.size() <= id) object_of_geometry_.resize(id + 1, -1);
    object_of_geometry_[id] = static_cast<int>(objects_.size() - 1);
  }
  rtcCommitScene(scene_);
  for (const PointLight& light : scene.point_lights) {
    int medium = -1;
    for (std::size_t i = 0; i < objects_.size() && medium < 0; ++i) {
      const ObjectData& d = objects_[i];
      if (!d.translucent || d.indices.empty()) continue;
      TriangleMesh world;
      world.positions = d.positions, world.indices = d.indices;
      if (open_edge_count(world) == 0 && encloses(world, glm::dvec3(light.position))) medium = static_cast<int>(i);
    }
    point_light_medium_.push_back(medium);
  }
}

double EmbreeScene::offset_at(const glm::dvec3& p) {
  return kRelativeOffset * std::max(largest_abs(p), 1e-30);
}

namespace {

// Embree's ray check (RayK::valid): finite origin and direction below FLT_LARGE, tnear >= 0, tfar not NaN (an
// empty interval tnear > tfar is a miss, decided before Embree).
void check_ray(const glm::dvec3& origin, const glm::dvec3& direction, double t_min, double t_max) {
  constexpr double kLargest = 1.8e18;
  const bool valid = glm::all(glm::lessThan(glm::abs(origin), glm::dvec3(kLargest))) &&
                     glm::all(glm::lessThan(glm::abs(direction), glm::dvec3(kLargest))) && t_min >= 0.0 &&
                     !std::isnan(t_max);  // false for NaN
  if (!valid)
    throw Error(fmt::format("internal error: a reference ray from ({}, {}, {}) along ({}, {}, {}) over [{}, {}] is "
                            "not finite; the scene's numbers are too large for single-precision ray tracing",
                            origin.x, origin.y, origin.z, direction.x, direction.y, direction.z, t_min, t_max));
}

}  // namespace


EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

SurfaceHit EmbreeScene::intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_max,
                                  double t_min) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(origin.x), rh.ray.org_y = static_cast<float>(origin.y);
  rh.ray.org_z = static_cast<float>(origin.z);
  rh.ray.dir_x = static_cast<float>(direction.x), rh.ray.dir_y = static_cast<float>(direction.y);
  rh.ray.dir_z = static_cast<float>(direction.z);
  const double t_near = t_min < 0.0 ? offset_at(origin) : t_min, t_far = std::min(t_max, 1e30);
  check_ray(origin, direction, t_near, t_far);
  if (t_far < t_near) return SurfaceHit{};  // an empty segment (shorter than the offset): nothing on it
  rh.ray.tnear = static_cast<float>(t_near);
  rh.ray.tfar = static_cast<float>(t_far);
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rh);
  SurfaceHit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.object = object_of_geometry_[rh.hit.geomID];
  hit.triangle = static_cast<int>(rh.hit.primID);
  hit.t = rh.ray.tfar;
  const ObjectData::Corners& c = objects_[static_cast<std::size_t>(hit.object)].corners[rh.hit.primID];
  double u = rh.hit.u, v = rh.hit.v;
  // The point from its barycentrics, in double: on the triangle's plane up to double rounding whatever the
  // ray's length (origin + t direction is off the plane by t's float rounding, which grows with the distance).
  hit.position = (1.0 - u - v) * glm::dvec3(c.position[0]) + u * glm::dvec3(c.position[1]) + v * glm::dvec3(c.position[2]);
  hit.offset = kRelativeOffset * std::max<double>(largest_abs(hit.position), c.magnitude);
  glm::dvec3 n = (1.0 - u - v) * glm::dvec3(c.normal[0]) + u * glm::dvec3(c.normal[1]) + v * glm::dvec3(c.normal[2]);
  hit.normal = glm::normalize(n);
  glm::dvec3 ng = glm::normalize(glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
  hit.geometric_normal = glm::dot(ng, hit.normal) < 0.0 ? -ng : ng;
  hit.uv = corner_uv(objects_[static_cast<std::size_t>(hit.object)], rh.hit.primID, u, v);
  return hit;
}

bool EmbreeScene::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_max) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = static_cast<float>(origin.x), ray.org_y = static_cast<float>(origin.y);
  ray.org_z = static_cast<float>(origin.z);
  ray.dir_x = static_cast<float>(direction.x), ray.dir_y = static_cast<float>(direction.y);
  ray.dir_z = static_cast<float>(direction.z);
  const double t_near = offset_at(origin), t_far = std::min(t_max, 1e30);
  check_ray(origin, direction, t_near, t_far);
  if (t_far < t_near) return false;  // a shadow segment shorter than the offset: nothing in between
  ray.tnear = static_cast<float>(t_near);
  ray.tfar = static_cast<float>(t_far);
  ray.mask = 0xffffffffu;
  rtcOccluded1(scene_, &context, &ray);
  return ray.tfar < 0.0f;
}

namespace {


}  // namespace

// The foot of the perpendicular from p to the triangle's plane is the nearest point when it lies inside the
// triangle (all three barycentric coordinates >= 0); otherwise the nearest point is on the boundary, the nearest of
// the three edges' nearest points (the distance to the plane's points grows away from the foot, so its minimum over
// the triangle, a convex set, lies on the boundary when the foot is outside).

namespace {

struct ClosestQuery {
  const EmbreeScene* scene;
  const std::vector<int>* object_of_geometry;
  glm::dvec3 point;
  double distance;
  double slack;  // how far p's float copy, the point Embree culls around, may be from p
};

// Embree calls this for every triangle whose bounds reach the query's sphere: the sphere shrinks to the nearest
// distance found plus the slack (rounded up to a float, so that no nearer triangle is skipped).
bool closest_triangle_callback(RTCPointQueryFunctionArguments* args) {
  auto* q = static_cast<ClosestQuery*>(args->userPtr);
  const int object = (*q->object_of_geometry)[args->geomID];
  const ObjectData::Corners& c = q->scene->object(object).corners[args->primID];
  const glm::dvec3 nearest = closest_point_on_triangle(q->point, glm::dvec3(c.position[0]), glm::dvec3(c.position[1]),
                                                       glm::dvec3(c.position[2]));
  const double d = glm::length(nearest - q->point);
  if (!(d < q->distance)) return false;
  q->distance = d;
  args->query->radius = std::nextafter(static_cast<float>(d + q->slack), std::numeric_limits<float>::max());
  return true;
}

}  // namespace

namespace {

struct WithinQuery {
  const EmbreeScene* scene;
  const std::vector<int>* object_of_geometry;
  glm::dvec3 point;
  double reach;  // the radius plus the float slack
  bool found;
  double distance;
};

// The first triangle within reach ends the query: the sphere shrinks to nothing.
bool within_callback(RTCPointQueryFunctionArguments* args) {
  auto* q = static_cast<WithinQuery*>(args->userPtr);
  if (q->found) return false;
  const int object = (*q->object_of_geometry)[args->geomID];
  const ObjectData::Corners& c = q->scene->object(object).corners[args->primID];
  const double d = glm::length(closest_point_on_triangle(q->point, glm::dvec3(c.position[0]), glm::dvec3(c.position[1]),
                                                         glm::dvec3(c.position[2])) -
                               q->point);
  if (!(d < q->reach)) return false;
  q->found = true;
  q->distance = d;
  args->query->radius = 0.0f;
  return true;
}

// Embree's point query about p's float copy, out to `reach` (rounded up in float), calling `callback` with `data`.
void point_query(RTCScene scene, const glm::dvec3& p, double reach, RTCPointQueryFunction callback, void* data) {
  RTCPointQuery query{};
  query.x = static_cast<float>(p.x), query.y = static_cast<float>(p.y), query.z = static_cast<float>(p.z);
  query.time = 0.0f;
  query.radius = std::nextafter(static_cast<float>(reach), std::numeric_limits<float>::max());
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(scene, &query, &context, callback, data);
}

}  // namespace

bool EmbreeScene::surface_within(const glm::dvec3& p, double radius, double& found_distance) const {
  const double slack = 4.0 * offset_at(p);
  WithinQuery q{this, &object_of_geometry_, p, radius + slack, false, 0.0};
  point_query(scene_, p, radius + slack, within_callback, &q);
  found_distance = q.distance;
  return q.found;
}

double EmbreeScene::closest_surface_distance(const glm::dvec3& p, double max_radius) const {
  // Embree culls around p in float: a triangle nearer to p than some distance is nearer to that point than the
  // distance plus theirs, which the slack covers (and subtracted from the result, keeps it a lower bound).
  const double slack = 4.0 * offset_at(p);
  ClosestQuery q{this, &object_of_geometry_, p, max_radius + slack, slack};
  point_query(scene_, p, max_radius + slack, closest_triangle_callback, &q);
  return std::clamp(q.distance - slack, 0.0, max_radius);
}

SurfaceSample EmbreeScene::sample_surface(int object, double u0, double u1, double u2, double u3) const {
  const ObjectData& d = objects_[static_cast<std::size_t>(object)];
  const std::size_t triangle = d.triangle_by_area.sample(u0, u1);
  const ObjectData::Corners& c = d.corners[triangle];
  // Uniform barycentrics (square-root mapping).
  double s = std::sqrt(u2), b0 = 1.0 - s, b1 = u3 * s, b2 = 1.0 - b0 - b1;
  glm::dvec3 p = b0 * glm::dvec3(c.position[0]) + b1 * glm::dvec3(c.position[1]) + b2 * glm::dvec3(c.position[2]);
  glm::dvec3 n = b0 * glm::dvec3(c.normal[0]) + b1 * glm::dvec3(c.normal[1]) + b2 * glm::dvec3(c.normal[2]);
  const double offset = kRelativeOffset * std::max<double>(largest_abs(p), c.magnitude);
  return {p, glm::normalize(n), static_cast<int>(triangle), 1.0 / d.area,
          corner_uv(d, static_cast<unsigned>(triangle), b1, b2), offset};
}

}  // namespace lucent::reference
