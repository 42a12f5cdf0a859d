// random_walk.cpp: see random_walk.h.
#include "transport/random_walk.h"

#include <cmath>

#include "bssrdf/fresnel.h"

namespace lucent::reference {

double sample_free_flight(Rng& rng, double sigma_t) { return -std::log(1.0 - rng.uniform()) / sigma_t; }

void orthonormal_basis(const glm::dvec3& w, glm::dvec3& u, glm::dvec3& v) {
  // Duff et al. 2017, "Building an Orthonormal Basis, Revisited".
  double sign = std::copysign(1.0, w.z);
  double a = -1.0 / (sign + w.z), b = w.x * w.y * a;
  u = glm::dvec3(1.0 + sign * w.x * w.x * a, sign * b, -sign * w.x);
  v = glm::dvec3(b, sign + w.y * w.y * a, -w.y);
}

double henyey_greenstein_pdf(double cos_theta, double g) {
  double denominator = 1.0 + g * g - 2.0 * g * cos_theta;
  return (1.0 - g * g) / (4.0 * M_PI * denominator * std::sqrt(denominator));
}

glm::dvec3 henyey_greenstein_pdf_bands(double cos_theta, const glm::dvec3& g) {
  return {henyey_greenstein_pdf(cos_theta, g.x), henyey_greenstein_pdf(cos_theta, g.y),
          henyey_greenstein_pdf(cos_theta, g.z)};
}

glm::dvec3 sample_henyey_greenstein(Rng& rng, const glm::dvec3& direction, double g) {
  double xi = rng.uniform();
  double cos_theta;
  if (std::abs(g) < 1e-4) {
    cos_theta = 1.0 - 2.0 * xi;
  } else {
    double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
    cos_theta = (1.0 + g * g - s * s) / (2.0 * g);
  }
  cos_theta = glm::clamp(cos_theta, -1.0, 1.0);
  double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  double phi = 2.0 * M_PI * rng.uniform();
  glm::dvec3 u, v;
  orthonormal_basis(direction, u, v);
  return glm::normalize(sin_theta * std::cos(phi) * u + sin_theta * std::sin(phi) * v + cos_theta * direction);
}

double dielectric_reflectance(const glm::dvec3& direction, const glm::dvec3& normal, double eta_ratio) {
  double cos_i = std::abs(glm::dot(direction, normal));
  return shader::fresnel_reflectance(static_cast<float>(eta_ratio), static_cast<float>(cos_i));
}

glm::dvec3 reflect(const glm::dvec3& direction, const glm::dvec3& normal) {
  return direction - 2.0 * glm::dot(direction, normal) * normal;
}

glm::dvec3 refract(const glm::dvec3& direction, const glm::dvec3& normal, double eta_ratio) {
  // Orient the normal against the incoming direction.
  glm::dvec3 n = glm::dot(direction, normal) < 0.0 ? normal : -normal;
  double cos_i = -glm::dot(direction, n);
  double sin2_t = (1.0 - cos_i * cos_i) / (eta_ratio * eta_ratio);
  double cos_t = std::sqrt(std::max(0.0, 1.0 - sin2_t));
  return glm::normalize(direction / eta_ratio + (cos_i / eta_ratio - cos_t) * n);
}

bool russian_roulette(Rng& rng, double& weight, double threshold, double survival) {
  if (weight >= threshold) return true;
  if (rng.uniform() >= survival) return false;
  weight /= survival;
  return true;
}

}  // namespace lucent::reference
