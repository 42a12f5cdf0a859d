// multipole.h: the multipole diffusion model of a slab of finite thickness, reflectance and transmittance.
//
// Source: Donner and Jensen, "Light Diffusion in Multi-Layered Translucent Materials", SIGGRAPH 2005, Section 3
// (eqs. 8-11). The standard dipole (standard_dipole.h) assumes the medium goes on forever below the surface; a slab
// of thickness d has two boundaries, and the fluence must vanish at both extrapolated boundaries, z = -z_b and
// z = d + z_b, z_b = 2 A D. An infinite row of dipoles mirrored about both does so: for i = -n..n,
//   z_r,i = 2 i (d + 2 z_b) + l,   z_v,i = 2 i (d + 2 z_b) - l - 2 z_b,   l = 1 / sigma_t'
// (i = 0 is Jensen et al.'s dipole). The radiant exitance through the top (reflectance) and the bottom
// (transmittance) at distance r from the entry point along the face:
//   R(r) = alpha' / (4 pi) sum_i [ z_r,i (1 + sigma_tr d_r,i) e^(-sigma_tr d_r,i) / d_r,i^3 - (same for z_v,i) ]
//   T(r) = alpha' / (4 pi) sum_i [ (d - z_r,i) (1 + sigma_tr d'_r,i) e^(-sigma_tr d'_r,i) / d'_r,i^3 - (same) ]
// with d_r,i = sqrt(r^2 + z_r,i^2) and d'_r,i = sqrt(r^2 + (d - z_r,i)^2). Each term integrates over the plane to
// alpha' / 2 sign(z) e^(-sigma_tr |z|), which gives the totals in closed form.
// Parameterisation: per colour band, like the standard dipole (same A from eta, same exit normalisation applies
// to S_d = R / (pi (1 - 2 C1(1/eta))); the caller applies the Fresnel transmission terms). The same eta on both faces.
// Known limits: a flat slab of uniform thickness (a curved or tapering part is approximated by the local thickness);
// depends on distance only; diffusion's bias at low albedo; for d below one reduced mean free path the real source
// lies at or below the bottom face (as the paper places it), where diffusion is least accurate.
#ifndef LUCENT_BSSRDF_MULTIPOLE_H
#define LUCENT_BSSRDF_MULTIPOLE_H
#include "shared/bridge.h"
#include "bssrdf/constants.h"
#include "bssrdf/medium.h"
#include "bssrdf/standard_dipole.h"

LUCENT_SHADER_BEGIN

// Dipole pairs on each side of i = 0 in the profiles (2 x 16 + 1 pairs). The pairs beyond i decay as
// e^(-sigma_tr 2 |i| (d + 2 z_b)) times the pair's own cancellation; at reduced albedo 0.999 and d of one mean free
// path that is e^-4 at i = 16, so the profiles of thin, nearly white slabs are truncated by a few percent at large r,
// where they are small; the totals below sum kMultipoleTotalPairs.
LUCENT_CONST int kMultipolePairs = 16;
LUCENT_CONST int kMultipoleTotalPairs = 512;

// z (1 + sigma_tr dist) e^(-sigma_tr dist) / dist^3, dist = sqrt(r^2 + z^2): one source's term.
LUCENT_INLINE float multipole_source_term(float z, float r, float sigma_tr) {
  float dist = sqrt(r * r + z * z);
  return z * (1.0f + sigma_tr * dist) * exp(-sigma_tr * dist) / (dist * dist * dist);
}

// One source at depth z and its row of mirrored dipoles (kMultipolePairs pairs on each side), without alpha' / (4 pi):
// x through the top face, y through the bottom face at distance r.
LUCENT_INLINE vec2 multipole_row(float z, float z_b, float thickness, float r, float sigma_tr) {
  float period = 2.0f * (thickness + 2.0f * z_b);
  vec2 sum = vec2(0.0f);
  for (int k = 0; k < 2 * kMultipolePairs + 1; ++k) {
    float shift = float(k - kMultipolePairs) * period;
    float z_r = shift + z, z_v = shift - z - 2.0f * z_b;
    sum.x += multipole_source_term(z_r, r, sigma_tr) - multipole_source_term(z_v, r, sigma_tr);
    sum.y += multipole_source_term(thickness - z_r, r, sigma_tr) - multipole_source_term(thickness - z_v, r, sigma_tr);
  }
  return sum;
}

// The reflectance and transmittance profiles (x: R(r), y: T(r)) [1/length^2] of a slab `thickness` thick
// [length] (one band): T at distance r along the bottom face from the point below the entry point.
LUCENT_INLINE vec2 multipole_profiles(BandMedium m, float eta, float thickness, float r) {
  float z_b = 2.0f * standard_dipole_A(eta) * m.D;
  float l = 1.0f / m.sigma_t_prime;
  return m.alpha_prime / (4.0f * kPi) * multipole_row(l, z_b, thickness, r, m.sigma_tr);
}

LUCENT_INLINE float multipole_Rd(BandMedium m, float eta, float thickness, float r) {
  return multipole_profiles(m, eta, thickness, r).x;
}
LUCENT_INLINE float multipole_Td(BandMedium m, float eta, float thickness, float r) {
  return multipole_profiles(m, eta, thickness, r).y;
}

// sign(z) e^(-sigma_tr |z|): a source's term integrated over the plane, without alpha' / 2.
LUCENT_INLINE float multipole_source_total(float z, float sigma_tr) {
  return (z > 0.0f ? 1.0f : (z < 0.0f ? -1.0f : 0.0f)) * exp(-sigma_tr * abs(z));
}

// Total reflectance and transmittance (the integrals of 2 pi r R and 2 pi r T), in units where sigma_t' = 1: the
// reduced albedo alpha', eta and the optical thickness sigma_t' d. x: reflectance, y: transmittance.
LUCENT_INLINE vec2 multipole_totals(float alpha_prime, float eta, float optical_thickness) {
  float sigma_tr = sqrt(3.0f * (1.0f - alpha_prime));  // sigma_tr / sigma_t'
  float z_b = 2.0f * standard_dipole_A(eta) / 3.0f;     // 2 A D with D = 1 / 3
  float period = 2.0f * (optical_thickness + 2.0f * z_b);
  float reflectance = 0.0f, transmittance = 0.0f;
  for (int k = 0; k < 2 * kMultipoleTotalPairs + 1; ++k) {
    float shift = float(k - kMultipoleTotalPairs) * period;
    float z_r = shift + 1.0f, z_v = shift - 1.0f - 2.0f * z_b;
    reflectance += multipole_source_total(z_r, sigma_tr) - multipole_source_total(z_v, sigma_tr);
    transmittance += multipole_source_total(optical_thickness - z_r, sigma_tr) -
                     multipole_source_total(optical_thickness - z_v, sigma_tr);
  }
  return 0.5f * alpha_prime * vec2(reflectance, transmittance);
}

// The same totals with the refracted light spread along its beam, as photon beam diffusion (Habel et al. 2013) does
// for the half-space: a source of strength alpha' e^(-z) dz at each depth z of the slab (units of sigma_t' = 1),
// each with its own row of mirrored dipoles, instead of all of it at depth 1. Quadrature over u = 1 - e^(-z), in
// which the sources' strength is uniform: kMultipoleBeamSteps midpoints over [0, 1 - e^(-d)]. The light that
// crosses the slab unscattered is not included (it is the beam's own transmission, e^(-sigma_t d)).
LUCENT_CONST int kMultipoleBeamSteps = 64;

LUCENT_INLINE vec2 multipole_beam_totals(float alpha_prime, float eta, float optical_thickness) {
  float sigma_tr = sqrt(3.0f * (1.0f - alpha_prime));
  float z_b = 2.0f * standard_dipole_A(eta) / 3.0f;
  float period = 2.0f * (optical_thickness + 2.0f * z_b);
  float u_end = 1.0f - exp(-optical_thickness);
  vec2 sum = vec2(0.0f);
  for (int s = 0; s < kMultipoleBeamSteps; ++s) {
    float z = -log(1.0f - (float(s) + 0.5f) / float(kMultipoleBeamSteps) * u_end);
    for (int k = 0; k < 2 * kMultipolePairs + 1; ++k) {
      float shift = float(k - kMultipolePairs) * period;
      float z_r = shift + z, z_v = shift - z - 2.0f * z_b;
      sum.x += multipole_source_total(z_r, sigma_tr) - multipole_source_total(z_v, sigma_tr);
      sum.y += multipole_source_total(optical_thickness - z_r, sigma_tr) -
               multipole_source_total(optical_thickness - z_v, sigma_tr);
    }
  }
  return 0.5f * alpha_prime * u_end / float(kMultipoleBeamSteps) * sum;
}

// The profiles with the refracted light spread along its beam (the totals above are their plane integrals): R(r)
// and T(r) [1/length^2] for a slab `thickness` thick, from `depth_steps` depths (at most kMultipoleBeamSteps; the
// totals use all of them). Each depth costs 2 (2 kMultipolePairs + 1) exponentials: a reference evaluation, too
// costly per sample for a renderer, which would tabulate it.
LUCENT_INLINE vec2 multipole_beam_profiles(BandMedium m, float eta, float thickness, float r, int depth_steps) {
  float z_b = 2.0f * standard_dipole_A(eta) * m.D;
  float u_end = 1.0f - exp(-m.sigma_t_prime * thickness);
  vec2 sum = vec2(0.0f);
  for (int s = 0; s < kMultipoleBeamSteps && s < depth_steps; ++s) {
    float z = -log(1.0f - (float(s) + 0.5f) / float(depth_steps) * u_end) / m.sigma_t_prime;
    sum += multipole_row(z, z_b, thickness, r, m.sigma_tr);
  }
  return m.alpha_prime / (4.0f * kPi) * u_end / float(depth_steps) * sum;
}

LUCENT_SHADER_END

#endif
