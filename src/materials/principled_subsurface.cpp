// principled_subsurface.cpp: see principled_subsurface.h.
#include "materials/principled_subsurface.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent {
namespace {

constexpr double kAlphaPrimeMax = 0.999999;  // Cycles' answer at R_d >= 0.995, and its clamp on alpha

// c[0] + c[1] g + ... + c[7] g^7.
double polynomial(const std::array<double, 8>& c, double g) {
  double sum = 0.0;
  for (int k = 7; k >= 0; --k) sum = sum * g + c[static_cast<std::size_t>(k)];
  return sum;
}

// The six g-dependent shape parameters of the Wrenninge-Villemin-Hery fit (their table, as Cycles 3.4 uses it).
struct AlbedoFit {
  double a, b, c, d, e, f;
};

AlbedoFit albedo_fit(double g) {
  constexpr std::array<double, 8> kA{1.8260523782, -1.28451056436, -1.79904629312, 9.19393289202,
                                     -22.8215585862, 32.0234874259, -23.6264803333, 7.21067002658};
  constexpr std::array<double, 8> kBExponent{0.0, 31.1491581433, -201.847017512, 841.576016723,
                                             -2018.09288505, 2731.71560286, -1935.41424244, 559.009054474};
  constexpr std::array<double, 8> kC{1.09686102424, -0.394704063468, 1.05258115941, -8.83963712726,
                                     28.8643230661, -46.8802913581, 38.5402837518, -12.7181042538};
  constexpr std::array<double, 8> kD{0.496310210422, 0.360146581622, -2.15139309747, 17.8896899217,
                                     -55.2984010333, 82.065982243, -58.5106008578, 15.8478295021};
  constexpr std::array<double, 8> kEExponent{0.0, 76.7316253952, -594.356773233, 2448.8834203,
                                             -5576.68528998, 7116.60171912, -4763.54467887, 1303.5318055};
  constexpr std::array<double, 8> kF{2.40602999408, -2.51814844609, 9.18494908356, -79.2191708682,
                                     259.082868209, -403.613804597, 302.85712436, -87.4370473567};
  return {polynomial(kA, g),
          4.98511194385 + 0.127355959438 * std::exp(polynomial(kBExponent, g)),
          polynomial(kC, g),
          polynomial(kD, g),
          4.23190299701 + 0.00310603949088 * std::exp(polynomial(kEExponent, g)),
          polynomial(kF, g)};
}

[[noreturn]] void fail(const std::string& where, const std::string& problem) {
  throw Error(fmt::format("{}: {}", where, problem));
}

void check_unit_colour(const glm::vec3& c, const char* field, const std::string& where) {
  for (int band = 0; band < 3; ++band)
    if (!(c[band] >= 0.0f && c[band] <= 1.0f))
      fail(where, fmt::format("{}[{}] = {} is out of range; allowed range [0, 1] (linear RGB)", field, band, c[band]));
}

void check_inputs(const PrincipledSubsurface& p, double scale_mm, const std::string& where) {
  check_unit_colour(p.base_color, "base_color", where);
  check_unit_colour(p.subsurface_color, "subsurface_color", where);
  if (!(p.subsurface > 0.0f && p.subsurface <= 1.0f))
    fail(where, fmt::format("subsurface = {} is out of range; allowed range (0, 1] (0 is an opaque diffuse surface: "
                            "give the object an albedo instead)", p.subsurface));
  for (int band = 0; band < 3; ++band)
    if (!(p.subsurface_radius[band] > 0.0f && std::isfinite(p.subsurface_radius[band])))
      fail(where, fmt::format("subsurface_radius[{}] = {} is out of range; allowed range (0, inf) scene units", band,
                              p.subsurface_radius[band]));
  if (!std::isfinite(p.subsurface_ior)) fail(where, "subsurface_ior is not finite");
  if (!std::isfinite(p.subsurface_anisotropy)) fail(where, "subsurface_anisotropy is not finite");
  if (!(scale_mm > 0.0 && std::isfinite(scale_mm))) fail(where, fmt::format("scale_mm = {} must be > 0", scale_mm));
}

}  // namespace

double cycles_dipole_rd(double alpha_prime, double eta) {
  const double f_dr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
  const double four_thirds_a = 4.0 / 3.0 * (1.0 + f_dr) / (1.0 - f_dr);
  const double s = std::sqrt(3.0 * (1.0 - alpha_prime));
  return 0.5 * alpha_prime * (1.0 + std::exp(-four_thirds_a * s)) * std::exp(-s);
}

double cycles_alpha_prime(double rd, double eta) {
  if (rd < 1e-4) return 0.0;
  if (rd >= 0.995) return kAlphaPrimeMax;
  double lo = 0.0, hi = 1.0;  // R_d rises with alpha'
  for (int step = 0; step < 60; ++step) {
    const double mid = 0.5 * (lo + hi);
    (cycles_dipole_rd(mid, eta) < rd ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double cycles_single_scattering_albedo(double albedo, double g) {
  const AlbedoFit fit = albedo_fit(g);
  const double blend = std::pow(albedo, 0.25);
  const double alpha = (1.0 - blend) * fit.a * std::pow(std::atan(fit.b * albedo), fit.c) +
                       blend * fit.d * std::pow(std::atan(fit.e * albedo), fit.f);
  return std::clamp(alpha, 0.0, kAlphaPrimeMax);
}

PrincipledConversion principled_subsurface_material(const PrincipledSubsurface& p, double scale_mm,
                                                    const std::string& where) {
  check_inputs(p, scale_mm, where);
  PrincipledConversion out;
  const double factor = p.subsurface;
  const double eta = std::clamp(static_cast<double>(p.subsurface_ior), 1.01, 3.8);
  const double g = std::clamp(static_cast<double>(p.subsurface_anisotropy), 0.0, 0.9);
  Material& m = out.material;
  for (int band = 0; band < 3; ++band) {
    // Colour and radius as the Principled node mixes and scales them.
    const double a = (1.0 - factor) * p.base_color[band] + factor * p.subsurface_color[band];
    if (!(a > 0.0))
      fail(where, fmt::format("the mixed colour (base_color and subsurface_color by subsurface) is 0 in band {}: a "
                              "black medium does not scatter; give the object an albedo instead", band));
    double d = p.subsurface_radius[band] * factor * scale_mm;
    // The method's radius scaling (bssrdf_setup_radius).
    if (p.method == PrincipledMethod::RandomWalk) {
      out.alpha_prime[band] = cycles_alpha_prime(a, eta);
      d *= std::sqrt(3.0 * (1.0 - out.alpha_prime[band]));
    } else {
      d *= 0.25 / M_PI;
    }
    // Extinction and single-scattering albedo (subsurface_random_walk_remap).
    const double sigma_t = 1.0 / (std::max(d, 1e-16) * (1.0 - g));
    out.albedo[band] = a;
    out.radius_mm[band] = d;
    out.alpha[band] = cycles_single_scattering_albedo(a, g);
    m.sigma_s[band] = static_cast<float>(out.alpha[band] * sigma_t);
    m.sigma_a[band] = static_cast<float>((1.0 - out.alpha[band]) * sigma_t);
  }
  m.g = glm::vec3(static_cast<float>(g));
  m.eta = 1.0f;  // index-matched, as Cycles' walk
  validate_material(m, where);
  return out;
}

PrincipledSubsurface principled_v1_equivalent(const PrincipledV2Subsurface& p, const std::string& where) {
  check_unit_colour(p.base_color, "base_color", where);
  // The Principled node gives the subsurface closure base_color * weight and a diffuse closure
  // base_color * (1 - weight) (svm/closure.h): a mix lucent cannot put on one translucent object.
  if (p.subsurface_weight != 1.0f)
    fail(where, fmt::format("subsurface_weight = {}: Blender 4 mixes a diffuse surface (1 - weight) with the "
                            "subsurface medium (weight); lucent renders the medium alone (weight 1); a weight of 0 "
                            "is an opaque object (give it an albedo)", p.subsurface_weight));
  // Cycles skips the subsurface closure at scale 0 (PrincipledBsdfNode::has_surface_bssrdf).
  if (!(p.subsurface_scale > 0.0f && std::isfinite(p.subsurface_scale)))
    fail(where, fmt::format("subsurface_scale = {} is out of range; allowed range (0, inf) scene units (0 is an "
                            "opaque diffuse surface: give the object an albedo instead)", p.subsurface_scale));
  for (int band = 0; band < 3; ++band)
    if (!(p.subsurface_radius[band] > 0.0f && std::isfinite(p.subsurface_radius[band])))
      fail(where, fmt::format("subsurface_radius[{}] = {} is out of range; allowed range (0, inf) (times "
                              "subsurface_scale)", band, p.subsurface_radius[band]));
  for (int band = 0; band < 3; ++band)
    if (!(p.base_color[band] > 0.0f))
      fail(where, fmt::format("base_color[{}] = 0: Blender 4's subsurface albedo is the base colour, and a black "
                              "medium does not scatter; give the object an albedo instead", band));
  if (!std::isfinite(p.ior)) fail(where, "ior is not finite");
  PrincipledSubsurface v1;
  v1.base_color = p.base_color;
  v1.subsurface = 1.0f;
  v1.subsurface_color = p.base_color;  // v2's subsurface albedo is the clamped base colour
  v1.subsurface_radius = p.subsurface_radius * p.subsurface_scale;
  v1.subsurface_anisotropy = p.subsurface_anisotropy;
  if (p.method == PrincipledV2Method::RandomWalkSkin) {
    // bssrdf_setup_radius's albedo-dependent branch, at Subsurface IOR: Blender 3's random_walk.
    v1.method = PrincipledMethod::RandomWalk;
    v1.subsurface_ior = p.subsurface_ior;
  } else {
    // bssrdf_setup_radius's 1 / (4 pi) branch: Blender 3's random_walk_fixed_radius; the IOR is not used.
    v1.method = PrincipledMethod::RandomWalkFixedRadius;
    v1.subsurface_ior = p.ior;
  }
  return v1;
}

PrincipledConversion principled_v2_subsurface_material(const PrincipledV2Subsurface& p, double scale_mm,
                                                       const std::string& where) {
  return principled_subsurface_material(principled_v1_equivalent(p, where), scale_mm, where);
}

}  // namespace lucent
