// direct_light.cpp: direct illumination of opaque Lambertian surfaces, shared by both references.
#include <cmath>

#include "lights/point_light.h"
#include "reference/integrators.h"

namespace lucent::reference {

namespace {

// 1 or 0 from a shadow ray, or with `rng` the transmittance through index-matched media on the way.
glm::dvec3 visibility(const ReferenceScene& s, glm::dvec3 origin, glm::dvec3 direction, double t_max, Rng* rng) {
  if (rng) return shadow_transmittance(s, origin, direction, t_max, *rng);
  return glm::dvec3(s.rt.occluded(origin, direction, t_max) ? 0.0 : 1.0);
}

}  // namespace

glm::dvec3 point_light_intensity(const ReferenceScene& s, const PointLight& light, glm::dvec3 direction) {
  glm::dvec3 I(intensity_in_scene_units(light, s.scene.scale_mm));
  if (!light.spot) return I;
  return I * static_cast<double>(shader::spot_falloff(static_cast<float>(glm::dot(direction, glm::dvec3(light.direction))),
                                                      std::cos(glm::radians(light.inner_deg)),
                                                      std::cos(glm::radians(light.outer_deg))));
}

glm::dvec3 direct_light_lambertian(const ReferenceScene& s, const SurfaceHit& hit, glm::dvec3 normal, Rng* rng) {
  const ObjectData& object = s.rt.object(hit.object);
  glm::dvec3 L(0.0);
  glm::dvec3 origin = hit.position + hit.offset * normal;
  for (const DirectionalLight& light : s.scene.lights) {
    glm::dvec3 to_light = -glm::dvec3(light.direction);
    double cos_l = glm::dot(normal, to_light);
    if (cos_l <= 0.0) continue;
    const glm::dvec3 T = visibility(s, origin, to_light, 1e30, rng);
    L += object.albedo / M_PI * glm::dvec3(light.radiance) * cos_l * T;
  }
  for (const PointLight& light : s.scene.point_lights) {
    glm::dvec3 to_light = glm::dvec3(light.position) - hit.position;
    double d = glm::length(to_light);
    to_light /= d;
    double cos_l = glm::dot(normal, to_light);
    if (cos_l <= 0.0) continue;
    const glm::dvec3 T = visibility(s, origin, to_light, d - EmbreeScene::offset_at(glm::dvec3(light.position)), rng);
    L += object.albedo / M_PI * point_light_intensity(s, light, -to_light) * cos_l / (d * d) * T;
  }
  return L;
}

}  // namespace lucent::reference
