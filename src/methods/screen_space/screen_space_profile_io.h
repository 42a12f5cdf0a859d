// screen_space_profile_io.h: the screen-space method's diffusion profile, written once for the CPU kernel
// (screen_space_kernel.cpp) and the shaders (C++ and GLSL through shared/bridge.h; an *_io.h so that it is embedded
// with the shaders). One band, normalised to 1 over the plane; lengths in scene units.
//
// Burley's normalized diffusion (Christensen & Burley 2015): R(r) = s (e^{-s r} + e^{-s r / 3}) / (8 pi r), with the
// searchlight fit s = (1.85 - A + 7 |A - 0.8|^3) sigma_t', A the multiple-scattering albedo (the standard dipole's
// R_total, bssrdf/diffuse_albedo.h) and sigma_t' = sigma_a + sigma_s (1 - g). In u = s r the shape is the same for
// every material, so one sum of Gaussians fitted to it in u serves every band:
//
//   R_G(r) = sum_i w_i s^2 e^{-(s r)^2 / (2 v_i)} / (2 pi v_i),   sum_i w_i = 1,
//
// v_i the i-th Gaussian's variance per axis in units of 1 / s^2 (constants below: least squares in u R(u), see
// docs/methods/screen-space.md for the fit and its error).
//
// Transmittance through a slab of thickness d (Jimenez et al. 2010): light entering the back face uniformly with
// unit flux per area reaches a point of the front face, at distance sqrt(d^2 + rho^2) from a back point at lateral
// offset rho, with the profile's weight there; the front point collects
//
//   T(d) = integral_0^inf R(sqrt(d^2 + rho^2)) 2 pi rho d rho = integral_d^inf R(r) 2 pi r dr     (r dr = rho d rho)
//
//   Burley:    T(d) = (s / 4) integral_d^inf (e^{-s r} + e^{-s r / 3}) dr = (e^{-s d} + 3 e^{-s d / 3}) / 4
//   Gaussians: T(d) = sum_i w_i e^{-(s d)^2 / (2 v_i)}     (each Gaussian factors into its d and rho parts)
//
// T(0) = 1 for both: at zero thickness all the light entering the back leaves through the front.
#ifndef LUCENT_METHODS_SCREEN_SPACE_PROFILE_IO_H
#define LUCENT_METHODS_SCREEN_SPACE_PROFILE_IO_H
#include "shared/bridge.h"
#include "bssrdf/diffuse_albedo.h"

#define LUCENT_SCREEN_SPACE_PROFILE_BURLEY 0
#define LUCENT_SCREEN_SPACE_PROFILE_GAUSSIANS 1

// The Gaussians fitted to Burley's shape in u = s r: weights (summing to 1) and variances [1 / s^2].
#define LUCENT_SCREEN_SPACE_GAUSSIANS 6
#define LUCENT_SCREEN_SPACE_GAUSSIAN_WEIGHTS 0.00647378f, 0.0251191f, 0.0755773f, 0.189193f, 0.344733f, 0.35890382f
#define LUCENT_SCREEN_SPACE_GAUSSIAN_VARIANCES 7.8015e-05f, 0.00201223f, 0.0262008f, 0.236841f, 1.73938f, 13.2367f

LUCENT_SHADER_BEGIN

#if defined(__cplusplus)
LUCENT_CONST float kScreenSpaceGaussianWeight[LUCENT_SCREEN_SPACE_GAUSSIANS] = {LUCENT_SCREEN_SPACE_GAUSSIAN_WEIGHTS};
LUCENT_CONST float kScreenSpaceGaussianVariance[LUCENT_SCREEN_SPACE_GAUSSIANS] = {LUCENT_SCREEN_SPACE_GAUSSIAN_VARIANCES};
#else
const float kScreenSpaceGaussianWeight[LUCENT_SCREEN_SPACE_GAUSSIANS] =
    float[LUCENT_SCREEN_SPACE_GAUSSIANS](LUCENT_SCREEN_SPACE_GAUSSIAN_WEIGHTS);
const float kScreenSpaceGaussianVariance[LUCENT_SCREEN_SPACE_GAUSSIANS] =
    float[LUCENT_SCREEN_SPACE_GAUSSIANS](LUCENT_SCREEN_SPACE_GAUSSIAN_VARIANCES);
#endif

// s [1 / length] of one band, from its coefficients in 1 / length.
LUCENT_INLINE float burley_scale(float sigma_a, float sigma_s, float g, float eta) {
  float A = diffuse_total_reflectance(sigma_a, sigma_s, g, eta);
  float d = abs(A - 0.8f);
  return (1.85f - A + 7.0f * d * d * d) * (sigma_a + sigma_s * (1.0f - g));
}

// T(d) of Burley's profile with scale s, thickness d >= 0 (same length unit).
LUCENT_INLINE float burley_transmittance(float s, float d) {
  return 0.25f * (exp(-s * d) + 3.0f * exp(-s * d / 3.0f));
}

// T(d) of the Gaussians fitted to Burley's profile with scale s.
LUCENT_INLINE float gaussians_transmittance(float s, float d) {
  float u2 = (s * d) * (s * d);
  float T = 0.0f;
  for (int i = 0; i < LUCENT_SCREEN_SPACE_GAUSSIANS; ++i)
    T += kScreenSpaceGaussianWeight[i] * exp(-u2 / (2.0f * kScreenSpaceGaussianVariance[i]));
  return T;
}

// T(d) of the profile LUCENT_SCREEN_SPACE_PROFILE_*.
LUCENT_INLINE float profile_transmittance(int profile, float s, float d) {
  return profile == LUCENT_SCREEN_SPACE_PROFILE_GAUSSIANS ? gaussians_transmittance(s, d) : burley_transmittance(s, d);
}

LUCENT_SHADER_END

#endif
