// model_total_reflectance.cpp: see model_total_reflectance.h.
#include "materials/model_total_reflectance.h"

#include <algorithm>
#include <cmath>

#include "bssrdf/model.h"

namespace lucent {
namespace {

constexpr int kRings = 6000;
constexpr int kAzimuths = 256;
constexpr int kExitSteps = 20000;

// integral over the hemisphere of T21(w_o) cos(theta_o) dw_o / pi = 2 integral_0^1 T(mu) mu dmu (midpoint rule).
double exit_transmittance(float eta) {
  double sum = 0.0;
  for (int k = 0; k < kExitSteps; ++k) {
    double mu = (k + 0.5) / kExitSteps;
    sum += shader::fresnel_transmittance(eta, static_cast<float>(mu)) * mu;
  }
  return 2.0 * sum / kExitSteps;
}

}  // namespace

ModelTotalReflectance model_total_reflectance(const Material& material, double incidence_deg) {
  ModelTotalReflectance out;
  out.exit_transmittance = exit_transmittance(material.eta);
  const double theta = incidence_deg * M_PI / 180.0;
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  const glm::vec3 w_i(static_cast<float>(std::sin(theta)), 0.0f, static_cast<float>(std::cos(theta)));
  // At normal incidence every model is rotationally symmetric about the entry point: one azimuth suffices.
  const int azimuths = incidence_deg == 0.0 ? 1 : kAzimuths;
  for (int band = 0; band < 3; ++band) {
    if (band > 0 && material.sigma_a[band] == material.sigma_a[band - 1] &&
        material.sigma_s[band] == material.sigma_s[band - 1] && material.g[band] == material.g[band - 1]) {
      out.radiosity[band] = out.radiosity[band - 1];
      out.total[band] = out.total[band - 1];
      continue;
    }
    // In units of the band's mean free path: the total does not depend on the length unit (S_d scales as
    // sigma_t^2 S_d(sigma_t r)), and float keeps its resolution for a mean free path of 1e-30 mm or 1e30 mm alike
    // (the rings' radii and S_d's values overflowed or underflowed there: NaN totals).
    const double sigma_t = static_cast<double>(material.sigma_a[band]) + static_cast<double>(material.sigma_s[band]);
    const double unit = sigma_t > 0.0 && std::isfinite(sigma_t) ? sigma_t : 1.0;
    shader::BandMedium m = shader::make_band_medium(static_cast<float>(material.sigma_a[band] / unit),
                                                    static_cast<float>(material.sigma_s[band] / unit), material.g[band]);
    m.thickness = static_cast<float>(material.thickness_mm * unit);
    const double r_min = 1e-6 / m.sigma_t_prime;
    const double r_max = 60.0 / std::min<double>(m.sigma_tr, m.sigma_t_prime);
    const double du = std::log(r_max / r_min) / kRings;
    double integral = 0.0;
    for (int k = 0; k < kRings; ++k) {
      const double r = r_min * std::exp((k + 0.5) * du);
      double ring = 0.0;
      for (int j = 0; j < azimuths; ++j) {
        const double phi = 2.0 * M_PI * (j + 0.5) / azimuths;
        const glm::vec3 x_o(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)), 0.0f);
        ring += shader::bssrdf_Sd(static_cast<int>(material.model), m, material.eta, glm::vec3(0.0f), w_i, n, x_o, n);
      }
      integral += ring * (2.0 * M_PI / azimuths) * r * r * du;  // dA = r dr dphi, dr = r du
    }
    // The disk inside r_min, at the value on its edge.
    integral += M_PI * r_min * r_min *
                shader::bssrdf_Sd(static_cast<int>(material.model), m, material.eta, glm::vec3(0.0f), w_i, n,
                                  glm::vec3(static_cast<float>(r_min), 0.0f, 0.0f), n);
    out.radiosity[band] = M_PI * integral;
    out.total[band] = integral * M_PI * out.exit_transmittance;
  }
  return out;
}

}  // namespace lucent
