// flat_slab_expectation.h: the flat slab of the texture-space, hybrid and local-global slab tests
// (tests/gl/test_flat_slab.cpp, tests/gl/test_local_global.cpp): its material, light and image size, and the
// radiance expected at its centre, computed from closed forms in double precision (nothing from a rendering).
#pragma once
#include <array>
#include <cmath>
#include <cstddef>

namespace lucent::test::flat_slab {

// Material [mm^-1] per band (g = 0): sigma_t' = 10 mm^-1 in every band, albedo 0.6, 0.75, 0.9. Diffusion lengths
// 1 / sigma_tr = 0.09, 0.12, 0.18 mm, z_r = 0.1 mm.
constexpr std::array<double, 3> kSigmaA = {4.0, 2.5, 1.0}, kSigmaS = {6.0, 7.5, 9.0};
constexpr double kEta = 1.3;
// Coloured irradiance on a surface facing the light, so that a mix-up of bands shows.
constexpr std::array<double, 3> kIrradiance = {1.5, 2.0, 2.5};
constexpr int kSize = 16;  // image width and height [pixels]

// F_t = 1 - F_r of the unpolarised Fresnel equations at normal incidence.
inline double fresnel_transmittance_normal(double eta) {
  const double r = (eta - 1.0) / (eta + 1.0);
  return 1.0 - r * r;
}

// The standard dipole's closed-form total diffuse reflectance, A from the Groenhuis F_dr (the spec's Section 2).
inline double dipole_total_reflectance(double sigma_a, double sigma_s, double eta) {
  const double alpha = sigma_s / (sigma_a + sigma_s);
  const double f_dr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
  const double A = (1.0 + f_dr) / (1.0 - f_dr);
  const double s = std::sqrt(3.0 * (1.0 - alpha));
  return 0.5 * alpha * (1.0 + std::exp(-(4.0 / 3.0) * A * s)) * std::exp(-s);
}

// Radiance of band b at the centre, seen along the normal: L = F_t E R_total F_t / (pi (1 - 2 C1(1/eta))), the
// last factor the standard dipole's exit normalisation with the spec's exactly integrated moment
// (C_phi(1/1.3) = 0.234717, so 1 - 2 C1(1/1.3) = 4 x 0.234717).
inline double expected_radiance(std::size_t b) {
  const double F_t = fresnel_transmittance_normal(kEta);
  return F_t * kIrradiance[b] * dipole_total_reflectance(kSigmaA[b], kSigmaS[b], kEta) * F_t / (M_PI * 4.0 * 0.234717);
}

}  // namespace lucent::test::flat_slab
