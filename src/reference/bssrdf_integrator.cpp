// bssrdf_integrator.cpp: the model reference (see integrators.h).
#include <algorithm>
#include <cmath>

#include "bssrdf/model.h"
#include "reference/integrators.h"

namespace lucent::reference {
namespace {

// B(x_o) / pi for one area sample of the object's surface (eq. 7 of Dal Corso et al., divided by pi).
glm::dvec3 scattered_radiosity_over_pi(const ReferenceScene& s, int object, glm::dvec3 x_o, glm::dvec3 n_o, Rng& rng) {
  const ObjectData& o = s.rt.object(object);
  SurfaceSample x_i = s.rt.sample_surface(object, rng.uniform(), rng.uniform(), rng.uniform());
  // Russian roulette on the exponential falloff of the band that reaches farthest.
  shader::BandMedium media[3];
  double sigma_tr_min = 1e30;
  for (int c = 0; c < 3; ++c) {
    media[c] = shader::make_band_medium(static_cast<float>(o.sigma_a[c]), static_cast<float>(o.sigma_s[c]),
                                        static_cast<float>(o.g[c]));
    sigma_tr_min = std::min(sigma_tr_min, static_cast<double>(media[c].sigma_tr));
  }
  double r = glm::length(x_o - x_i.position);
  double keep = std::exp(-sigma_tr_min * r);
  if (rng.uniform() >= keep) return glm::dvec3(0.0);
  glm::dvec3 sum(0.0);
  for (const DirectionalLight& light : s.scene.lights) {
    glm::dvec3 w_i = -glm::dvec3(light.direction);
    double cos_i = glm::dot(x_i.normal, w_i);
    if (cos_i <= 0.0 || s.rt.occluded(x_i.position + s.rt.ray_epsilon() * x_i.normal, w_i)) continue;
    double T12 = shader::fresnel_transmittance(static_cast<float>(o.eta), static_cast<float>(cos_i));
    for (int c = 0; c < 3; ++c) {
      double S_d = shader::bssrdf_Sd(o.model, media[c], static_cast<float>(o.eta), glm::vec3(x_i.position),
                                     glm::vec3(w_i), glm::vec3(x_i.normal), glm::vec3(x_o), glm::vec3(n_o));
      sum[c] += light.radiance[c] * S_d * T12 * cos_i;
    }
  }
  // B = pi E integral(S_d T12 cos dA); estimator divides by the area pdf and the roulette probability.
  return sum / (x_i.pdf_area * keep);
}

}  // namespace

glm::dvec3 bssrdf_radiance(const ReferenceScene& s, glm::dvec3 origin, glm::dvec3 direction, Rng& rng) {
  SurfaceHit hit = s.rt.intersect(origin, direction);
  if (!hit.hit()) return glm::dvec3(s.scene.render.background);
  const ObjectData& o = s.rt.object(hit.object);
  glm::dvec3 n = hit.normal;
  if (!o.translucent) {
    if (glm::dot(n, direction) > 0.0) n = -n;
    return direct_light_lambertian(s, hit, n);
  }
  double cos_o = std::max(0.0, -glm::dot(n, direction));
  double T21 = shader::fresnel_transmittance(static_cast<float>(o.eta), static_cast<float>(cos_o));
  return T21 * scattered_radiosity_over_pi(s, hit.object, hit.position, n, rng);
}

}  // namespace lucent::reference
