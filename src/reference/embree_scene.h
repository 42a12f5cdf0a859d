// embree_scene.h: a lucent::Scene as an Embree 3 ray-tracing scene for the CPU references: world-space
// triangles, one Embree geometry per object, interpolated shading normals, materials in scene units and
// uniform area sampling of each object's surface.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "lucent/scene.h"
#include "geometry/flat_patches.h"
#include "reference/alias_table.h"

namespace lucent::reference {

struct SurfaceHit {
  double t = 0.0;
  int object = -1;           // index into Scene::objects; -1 = miss
  int triangle = -1;         // the triangle's index in the object (ObjectData::corners)
  glm::dvec3 position{0.0};  // [scene units]
  glm::dvec3 normal{0.0};    // interpolated shading normal, unit, pointing out of the object
  glm::dvec3 geometric_normal{0.0};  // unit, on the same side as `normal`
  glm::dvec2 uv{0.0};        // texture coordinates (only for objects with a textured material; else 0)
  // How far a ray leaving this point starts from it, along the geometric normal, to not hit the surface again
  // [scene units]: EmbreeScene::kRelativeOffset of the largest coordinate of the point and of its triangle's
  // corners, i.e. a few float rounding steps of the numbers the intersection was computed from.
  double offset = 0.0;
  bool hit() const { return object >= 0; }
};

// A medium's coefficients at one point [1/scene unit], unreduced sigma_s.
struct MediumCoefficients {
  glm::dvec3 sigma_a{0.0}, sigma_s{0.0};
  glm::dvec3 sigma_t() const { return sigma_a + sigma_s; }
};

// Per object: optical properties in scene units and the data for area sampling.
struct ObjectData {
  bool translucent = false;
  glm::dvec3 albedo{0.0};
  glm::dvec3 sigma_a{0.0}, sigma_s{0.0}, g{0.0};  // [1/scene unit], unreduced sigma_s
  double eta = 1.0;
  int model = 1;                                  // LUCENT_MODEL_*
  double thickness = 0.0;                         // the multipole model's slab thickness [scene units]
  ThicknessGrid thickness_grid;                   // the same per surface point, when measured on the mesh
  // The multipole model's thickness at x [scene units]: the grid's where there is one, else `thickness`.
  double thickness_at(const glm::dvec3& x) const;
  // A textured material (lucent::MaterialMaps, coefficients in mm^-1) with each triangle's corner texture
  // coordinates; sigma_a and sigma_s above are then those of the maps' mean.
  std::shared_ptr<const MaterialMaps> maps;
  std::vector<std::array<glm::vec2, 3>> corner_uvs;
  bool textured() const { return maps != nullptr; }
  // The coefficients where light leaves (or a camera path enters) the surface at texture coordinates uv: the
  // maps' there, the material's for an untextured object.
  MediumCoefficients medium_at(glm::dvec2 uv) const;
  // Heterogeneous medium (media/heterogeneous_field.h): sigma_t(x) = m(x) sigma_t, sigma_s(x) = min(m, 1) sigma_s
  // over the world-space bounds [lower, upper]; `majorant` = max m sigma_t bounds sigma_t(x) for delta tracking.
  MediumField field;
  float scale_mm = 1.0f;                          // mm per scene unit (the field's feature sizes are in mm)
  glm::vec3 lower{0.0f}, upper{0.0f};
  glm::vec3 mesh_lower{0.0f}, mesh_upper{0.0f};   // the mesh's own bounds (lower/upper may be the field's)
  glm::dvec3 majorant{0.0};                       // [1/scene unit]
  bool heterogeneous() const { return field.heterogeneous(); }
  double multiplier(const glm::dvec3& p) const { return field.multiplier(glm::vec3(p), lower, upper, scale_mm); }
  double area = 0.0;                              // [scene units^2]
  AliasTable triangle_by_area;                    // picks a triangle with probability area / total area
  std::vector<glm::vec3> positions, normals;      // world space
  std::vector<std::uint32_t> indices;
  // The same triangles with their corners side by side (72 bytes, at most two cache lines), for the random
  // accesses of hits and area samples: a hit's normal from the indexed arrays cost three scattered loads after
  // the index load.
  struct Corners {
    glm::vec3 position[3], normal[3];
    float magnitude;  // the largest |coordinate| of the three positions
  };
  std::vector<Corners> corners;
  // Translucent objects, for the specular-chain solvers that walk on the boundary: each triangle's neighbour across
  // each edge (geometry/triangle_adjacency.h), and its plane: xyz the unit normal on the side of its corner normals,
  // w the square root of its area (its size).
  std::vector<std::array<std::int32_t, 3>> neighbours;
  std::vector<glm::vec4> planes;
  FlatPatches faces;  // its large flat faces (geometry/flat_patches.h)
};

struct SurfaceSample {
  glm::dvec3 position, normal;
  int triangle = -1;  // the triangle's index in the object
  double pdf_area;  // 1 / area
  glm::dvec2 uv{0.0};  // texture coordinates (textured objects only)
  double offset = 0.0;  // as SurfaceHit::offset
};


class EmbreeScene {
 public:
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Self-intersection offsets are relative to the magnitude of the coordinates involved, never to the scene's
  // size: a reference must not change when a large object is added far away, or when the whole scene is
  // expressed in other units. 1e-6 is about 8 float rounding steps (Embree intersects in float); an offset of
  // 1e-5 of the scene's radius put rays a mean free path deep into dense media beside a large floor.
  static constexpr double kRelativeOffset = 1e-6;
  // The offset for a ray leaving `p` when no hit is known: kRelativeOffset of p's largest |coordinate|.
  static double offset_at(const glm::dvec3& p);

  // The closest hit in (t_min, t_max]; t_min defaults to offset_at(origin) (rays leaving a surface point). Rays
  // from a medium's interior pass 0: a vertex within the offset of the boundary must not skip it. A ray with a
  // non-finite or out-of-range origin, direction or t_max is a lucent::Error (Embree's own check aborts).
  SurfaceHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_max = 1e30,
                       double t_min = -1.0) const;
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_max = 1e30) const;

  // The distance from `p` to the nearest triangle of any object, or `max_radius` when none is nearer (a smaller
  // radius visits fewer BVH nodes). The triangles are Embree's own (float corners); the result is lowered by a few
  // float rounding steps of p's coordinates, so that a ball of that radius about p touches no surface.
  double closest_surface_distance(const glm::dvec3& p, double max_radius) const;
  // Whether some surface may lie within `radius` of p (true also within float rounding of it: a conservative
  // answer), and then the distance to the first such triangle found (not the nearest: an upper bound of the
  // distance). Stops at the first triangle within reach: far cheaper than the nearest's distance in a fine mesh.
  bool surface_within(const glm::dvec3& p, double radius, double& found_distance) const;

  // The translucent object whose closed surface encloses point light `light` (an index into Scene::point_lights),
  // or -1 when it is in air.
  int medium_of_point_light(std::size_t light) const { return point_light_medium_[light]; }

  const ObjectData& object(int index) const { return objects_[static_cast<std::size_t>(index)]; }
  int object_count() const { return static_cast<int>(objects_.size()); }
  // A point uniform over the object's area from four uniforms (triangle: u0, u1; point in it: u2, u3).
  SurfaceSample sample_surface(int object, double u0, double u1, double u2, double u3) const;

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<ObjectData> objects_;
  std::vector<int> object_of_geometry_;
  std::vector<int> point_light_medium_;
};

}  // namespace lucent::reference
