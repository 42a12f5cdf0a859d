// direct_light.cpp: direct illumination of opaque Lambertian surfaces, shared by both references.
#include <cmath>

#include "reference/integrators.h"

namespace lucent::reference {

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
  return L;
}

}  // namespace lucent::reference
