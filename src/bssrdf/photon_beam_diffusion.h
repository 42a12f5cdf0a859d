// photon_beam_diffusion.h: the photon beam diffusion (PBD) BSSRDF.
//
// Source: Habel, Christensen, Jarosz, "Photon Beam Diffusion: A Hybrid Monte Carlo Method for Subsurface
// Scattering", CGF 32(4) (EGSR 2013), in the form of pbrt-v3's BeamDiffusionMS/BeamDiffusionSS (Pharr, Jakob,
// Humphreys, PBR 3rd ed., Section 15.5); equations as listed in shared/spec/bssrdf-models.md Section 3:
// improved diffusion (d'Eon & Irving 2011) with Grosjean's D_G (PBR eq. 15.24), sigma_tr = sqrt(sigma_a / D_G),
// extrapolated boundary z_b = 2 A D_G (PBR eq. 15.28), the dipole fluence and flux of one point source
// (PBR eq. 15.27) weighted into exitance by C_phi, C_E (PBR eqs. 15.31-15.32), and the beam integral over
// point-source depths z_r with density sigma_t' e^{-sigma_t' z_r}, factor rho'^2 and the correction
// kappa = 1 - e^{-2 sigma_t' (d_r + z_r)}.
// Clamp: d_r >= 0.25 / (sigma_a + sigma_t) wherever d_r is a denominator (Dal Corso et al. 2015, Section 6,
// text of Fig. 14: the weak singularity at r -> 0 otherwise gives fireflies); sigma_t is the unreduced
// extinction, as in that paper's notation. The exponentials and kappa use the true d_r.
// Parameterisation: per colour band, lengths and coefficients in one consistent unit, S_d in 1/length^2.
// S_d = R_ms(|x_o - x_i|) / (pi (1 - 2 C1(1/eta))): the multiple-scattering exitance profile per unit refracted
// flux, turned into S_d with the normalisation of the directional dipole (spec Section 1.4) and of pbrt's
// separable BSSRDF, so that S = T12(w_i) S_d T21(w_o) as for the other models (Fresnel applied by the caller).
// Integration: midpoint rule in u = 1 - e^{-sigma_t' z_r} (pbrt's scheme) with kPhotonBeamSamples points.
// Measured against 2e4 points (double precision, sigma_t' = 1, eta 1.0/1.3/1.5, rho' 0.3-0.999, clamp on,
// 0 <= r <= 10/sigma_tr): g = 0 within 0.65% at every r, g = 0.5 within 1.1%, g = 0.9 (smaller clamp) within
// 0.63% for r >= 0.05/sigma_t' and 5.8% below; the total 2 pi int r R_ms dr within 0.11%. 16 points: 2.4%
// (g = 0) and 33% (g = 0.9, small r); 24 points: 1.3% and 17%. Cost (about 21x the directional dipole on the
// CPU) and the full table: docs/models/photon-beam-diffusion.md.
// Known limits: the beam is the surface normal (pbrt's form): S_d depends on |x_o - x_i| only, not on the
// incident direction or the normals (the paper refracts the beam); flat semi-infinite medium. Single
// scattering (photon_beam_single_scattering) is not part of S_d: it is the spec's separate S_SS term.
#ifndef LUCENT_BSSRDF_PHOTON_BEAM_DIFFUSION_H
#define LUCENT_BSSRDF_PHOTON_BEAM_DIFFUSION_H
#include "shared/bridge.h"
#include "bssrdf/constants.h"
#include "bssrdf/fresnel.h"
#include "bssrdf/medium.h"

LUCENT_SHADER_BEGIN

// Beam samples of photon_beam_diffusion_Sd (accuracy in the header comment; pbrt uses 100).
LUCENT_CONST int kPhotonBeamSamples = 32;

// Improved-diffusion constants of one band (spec Section 3).
struct PhotonBeamMedium {
  float sigma_t_prime;  // reduced extinction [1/length]
  float rho_prime;      // reduced albedo sigma_s' / sigma_t'
  float D_G;            // Grosjean diffusion coefficient (2 sigma_a + sigma_s') / (3 sigma_t'^2) [length]
  float sigma_tr;       // effective transport coefficient sqrt(sigma_a / D_G) [1/length]
  float z_b;            // extrapolated boundary height 2 A D_G, A = (1 + 3 C2) / (1 - 2 C1) [length]
  float c_phi;          // exitance weight of the fluence (1 - 2 C1) / 4
  float c_e;            // exitance weight of the flux (1 - 3 C2) / 2
};

LUCENT_INLINE PhotonBeamMedium make_photon_beam_medium(BandMedium m, float eta) {
  PhotonBeamMedium p;
  p.sigma_t_prime = m.sigma_t_prime;
  p.rho_prime = m.alpha_prime;
  p.D_G = (2.0f * m.sigma_a + m.sigma_s_prime) / (3.0f * m.sigma_t_prime * m.sigma_t_prime);
  p.sigma_tr = sqrt(m.sigma_a / p.D_G);
  p.c_phi = fresnel_c_phi(eta);
  p.c_e = fresnel_c_e(eta);
  p.z_b = 2.0f * p.D_G * (1.0f - p.c_e) / (2.0f * p.c_phi);
  return p;
}

// Smallest d_r in a denominator (Dal Corso et al. 2015, Section 6) [length].
LUCENT_INLINE float photon_beam_d_r_min(BandMedium m) { return 0.25f / (m.sigma_a + m.sigma_t); }

// Beam integrand without the sampled density: kappa E_d(r; z_r) for a real source at depth z_r and its
// virtual source at height z_r + 2 z_b, seen at distance r on the surface.
LUCENT_INLINE float photon_beam_integrand(PhotonBeamMedium p, float r, float z_r, float d_r_min) {
  float z_v = z_r + 2.0f * p.z_b;
  float d_r = sqrt(r * r + z_r * z_r);
  float d_v = sqrt(r * r + z_v * z_v);
  float d_r_den = max(d_r, d_r_min);
  float e_r = exp(-p.sigma_tr * d_r);
  float e_v = exp(-p.sigma_tr * d_v);
  // Fluence and normal flux of the dipole (PBR eq. 15.27), clamped denominators for the real source.
  float fluence = (e_r / d_r_den - e_v / d_v) / (4.0f * kPi * p.D_G);
  float flux = (z_r * (1.0f + p.sigma_tr * d_r) * e_r / (d_r_den * d_r_den * d_r_den) +
                z_v * (1.0f + p.sigma_tr * d_v) * e_v / (d_v * d_v * d_v)) /
               (4.0f * kPi);
  float kappa = 1.0f - exp(-2.0f * p.sigma_t_prime * (d_r + z_r));
  return kappa * (p.c_phi * fluence + p.c_e * flux);
}

// Multiple-scattering exitance profile R_ms(r) [1/length^2] per unit refracted flux (the spec's S_MS): the
// beam integral by the midpoint rule in u = 1 - e^{-sigma_t' z_r} with n_samples points. d_r_min = 0
// gives pbrt's unclamped BeamDiffusionMS (with n_samples = 100).
LUCENT_INLINE float photon_beam_diffusion_Rms(BandMedium m, float eta, float r, int n_samples, float d_r_min) {
  PhotonBeamMedium p = make_photon_beam_medium(m, eta);
  float sum = 0.0f;
  // loop bound: checked; kPhotonBeamSamples per S_d evaluation, which the shaders call once per BSSRDF sample: per-pixel and radiosity-maps count them in check_loop_iterations
  for (int i = 0; i < n_samples; ++i) {
    float z_r = -log(1.0f - (float(i) + 0.5f) / float(n_samples)) / p.sigma_t_prime;
    sum += photon_beam_integrand(p, r, z_r, d_r_min);
  }
  return p.rho_prime * p.rho_prime * sum / float(n_samples);
}

// S_d(x_i; x_o) [1/length^2] for one band: clamped beam integral with kPhotonBeamSamples points, normalised
// by 1 / (pi (1 - 2 C1(1/eta))) = 1 / (4 pi C_phi(1/eta)).
LUCENT_INLINE float photon_beam_diffusion_Sd(BandMedium m, float eta, vec3 x_i, vec3 x_o) {
  float R_ms = photon_beam_diffusion_Rms(m, eta, length(x_o - x_i), kPhotonBeamSamples, photon_beam_d_r_min(m));
  return R_ms * kInvPi / (4.0f * fresnel_c_phi(1.0f / eta));
}

// Henyey-Greenstein phase function [1/sr]; cos_theta between the propagation directions.
LUCENT_INLINE float henyey_greenstein(float cos_theta, float g) {
  float denom = 1.0f + g * g - 2.0f * g * cos_theta;
  return (1.0f - g * g) / (4.0f * kPi * denom * sqrt(denom));
}

// Single-scattering profile R_ss(r) [1/length^2] of a normally incident beam (the spec's S_SS; not part of
// S_d): scattering depths t >= t_c = r sqrt(eta^2 - 1) (below the critical angle), midpoint rule in
// u = 1 - e^{-sigma_t (t - t_c)} with n_samples points, unreduced sigma_t and albedo.
LUCENT_INLINE float photon_beam_single_scattering(BandMedium m, float eta, float r, int n_samples) {
  float rho = m.sigma_s / m.sigma_t;
  float t_c = r * sqrt(max(eta * eta - 1.0f, 0.0f));
  float sum = 0.0f;
  // loop bound: 0; no shader calls it (C++ only, the CPU tests)
  for (int i = 0; i < n_samples; ++i) {
    float t = t_c - log(1.0f - (float(i) + 0.5f) / float(n_samples)) / m.sigma_t;
    float d = sqrt(r * r + t * t);
    float cos_theta_o = t / d;
    // The beam travels down (-n), the scattered light up toward x_o: cos between them is -cos_theta_o.
    float phase = henyey_greenstein(-cos_theta_o, m.g);
    float T21 = fresnel_transmittance(1.0f / eta, cos_theta_o);
    sum += rho * exp(-m.sigma_t * (d + t_c)) / (d * d) * phase * T21 * cos_theta_o;
  }
  return sum / float(n_samples);
}

LUCENT_SHADER_END

#endif
