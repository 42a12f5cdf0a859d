// direct_light.cpp: direct illumination of opaque Lambertian surfaces, shared by both references.
#include <cmath>

#include "lights/point_light.h"
#include "reference/integrators.h"

namespace lucent::reference {

glm::dvec3 point_light_intensity(const ReferenceScene& s, const PointLight& light, glm::dvec3 direction) {
  glm::dvec3 I(intensity_in_scene_units(light, s.scene.scale_mm));
  if (!light.spot) return I;
  return I * static_cast<double>(shader::spot_falloff(static_cast<float>(glm::dot(direction, glm::dvec3(light.direction))),
                                                      std::cos(glm::radians(light.inner_deg)),
                                                      std::cos(glm::radians(light.outer_deg))));
}

glm::dvec3 direct_light_lambertian(const ReferenceScene& s, const SurfaceHit& hit, glm::dvec3 normal) {
  const ObjectData& object = s.rt.object(hit.object);
  glm::dvec3 L(0.0);
  glm::dvec3 origin = hit.position + s.rt.ray_epsilon() * normal;
  for (const DirectionalLight& light : s.scene.lights) {
    glm::dvec3 to_light = -glm::dvec3(light.direction);
    double cos_l = glm::dot(normal, to_light);
    if (cos_l <= 0.0 || s.rt.occluded(origin, to_light)) continue;
    L += object.albedo / M_PI * glm::dvec3(light.radiance) * cos_l;
  }
  for (const PointLight& light : s.scene.point_lights) {
    glm::dvec3 to_light = glm::dvec3(light.position) - hit.position;
    double d = glm::length(to_light);
    to_light /= d;
    double cos_l = glm::dot(normal, to_light);
    if (cos_l <= 0.0 || s.rt.occluded(origin, to_light, d - s.rt.ray_epsilon())) continue;
    L += object.albedo / M_PI * point_light_intensity(s, light, -to_light) * cos_l / (d * d);
  }
  return L;
}

}  // namespace lucent::reference
