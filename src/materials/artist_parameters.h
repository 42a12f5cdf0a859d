// artist_parameters.h: a translucent material from the two numbers artists set per colour band, the surface albedo
// and the mean free path, instead of the absorption and scattering coefficients.
//
// Definitions (docs/materials.md):
// - surface albedo A: the multiple-scattering albedo seen on a flat, thick (semi-infinite), uniformly lit slab,
//   i.e. the model's flat total diffuse reflectance per refracted power at normal incidence
//   (materials/model_total_reflectance.h), per band, in (0, 1);
// - mean free path mfp [mm]: the unreduced one, mfp = 1 / sigma_t = 1 / (sigma_a + sigma_s), as pbrt-v4's
//   subsurface material and OpenPBR define it. With forward scattering the transport mean free path
//   1 / sigma_t' = mfp / (1 - alpha g) is longer.
//
// Inversion, as pbrt-v4's SubsurfaceFromDiffuse does with its tabulated curve: a model's flat total depends only on
// the single-scattering albedo alpha = sigma_s / sigma_t, g and eta (not on the length scale), and rises
// monotonically with alpha. Per band, bisection on alpha finds total(alpha) = A; then sigma_s = alpha / mfp,
// sigma_a = (1 - alpha) / mfp.
//
// The tabulated model's curve is photon transport (seconds per band), too slow to search: its materials are
// inverted with the standard dipole's curve, the diffusion curve closest to exact transport over the albedo range
// (docs/models/total-reflectance.md: within 20% for alpha' >= 0.3 at eta 1.3, within 1% at 0.95 and above).
// `lucent materials invert` reports the total the tabulated model then gives.
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/material.h"

namespace lucent {

struct ArtistParameters {
  glm::vec3 albedo{0.8f};   // surface albedo: the model's flat total diffuse reflectance per band, (0, 1)
  glm::vec3 mfp_mm{1.0f};   // mean free path 1 / sigma_t per band (unreduced) [mm], > 0
  glm::vec3 g{0.0f};        // Henyey-Greenstein mean cosine per band (-1, 1)
  float eta = 1.3f;         // relative refractive index n_material / n_outside [1, 3]
  BssrdfModel model = kDefaultBssrdfModel;
};

// The alpha interval searched: alpha_max keeps sigma_a > 0, which every diffusion model needs.
inline constexpr double kArtistAlphaMin = 1e-6;
inline constexpr double kArtistAlphaMax = 1.0 - 1e-7;

// The model whose flat-total curve inverts materials of `model`: the model itself, the standard dipole for the
// tabulated and multipole models (their media are described by the half-space; a slab's thickness is geometry).
BssrdfModel inversion_curve_model(BssrdfModel model);

// The flat total diffuse reflectance at normal incidence of one band medium with single-scattering albedo `alpha`
// under `model` (not the tabulated model).
double flat_total_of_albedo(BssrdfModel model, double alpha, float g, float eta);

// The flat totals `model`'s inversion curve reaches at g and eta: (lowest, min(highest, 1)).
struct FlatTotalRange {
  double lowest = 0.0, highest = 1.0;
  bool contains(double albedo) const { return albedo > lowest && albedo < highest; }
};
FlatTotalRange flat_total_range(BssrdfModel model, float g, float eta);

// The models (standard, directional, photon-beam, better-dipole, in that order; not `model` nor its curve) whose
// ranges at eta and each band's g hold every albedo in [lo, hi].
std::vector<BssrdfModel> models_reaching(double lo, double hi, const glm::vec3& g, float eta, BssrdfModel model);

// The advice that ends an out-of-range message: "the standard and better-dipole models reach it (model
// \"standard\")", or "no lucent diffusion model reaches it at g ... and eta ...; ..." with the widest range.
std::string models_reaching_advice(double lo, double hi, const glm::vec3& g, float eta, BssrdfModel model);

struct ArtistInversion {
  Material material;             // coefficients in mm^-1, g, eta and the model asked for
  glm::dvec3 alpha{0.0};         // single-scattering albedo sigma_s / sigma_t per band
  glm::dvec3 total{0.0};         // the curve model's flat total with `material`'s float coefficients
  BssrdfModel curve_model = kDefaultBssrdfModel;
};

// Finds sigma_a, sigma_s per band. Throws lucent::Error("<where>: <field>[<band>] = <value> <problem>; <range>")
// for a NaN or infinite value, an albedo outside (0, 1) or outside the totals the model reaches, an mfp <= 0, g
// outside (-1, 1), eta outside [1, 3].
ArtistInversion invert_artist_parameters(const ArtistParameters& artist, const std::string& where);

}  // namespace lucent
