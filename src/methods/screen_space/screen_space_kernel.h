// screen_space_kernel.h: the screen-space method's blur kernel, computed on the CPU per material (no GL).
//
// Profile: Burley's normalized diffusion (Christensen & Burley 2015), R(r) = A s (e^{-s r} + e^{-s r / 3}) / (8 pi r),
// which integrates to A over the plane. Per band: A = the material's total diffuse reflectance R_total (the standard
// dipole's closed form, bssrdf/diffuse_albedo.h) as the multiple-scattering albedo, and the searchlight fit
// s = (1.85 - A + 7 |A - 0.8|^3) / l with l = 1 / sigma_t' the (reduced) mean free path. Or (`profile` "gaussians")
// the sum of Gaussians fitted to Burley's shape (screen_space_profile_io.h), with the same s.
//
// A separable blur applies a 1D kernel along each image axis. Its kernel is the profile's marginal
// P(x) = integral of R(sqrt(x^2 + y^2)) dy = A s (K0(s|x|) + K0(s|x| / 3)) / (4 pi), normalised to 1, so that a
// straight lit edge is blurred exactly as the 2D profile would blur it. In u = s x its cumulative distribution is
// material independent: C(u) = 1/2 + sign(u) H(|u|), H(v) = (G(v) + 3 G(v / 3)) / (4 pi), G(v) = integral_0^v K0.
// The Gaussians' marginal is exact per component: a 2D Gaussian of variance v per axis has the 1D Gaussian of variance
// v as its marginal, so H(v) = sum_i w_i erf(v / sqrt(2 v_i)) / 2.
//
// Taps (importance placed, as Jimenez et al. 2015 place theirs by the profile's distribution): the line is cut at the
// j / N quantiles of the three bands' mean marginal into N intervals of equal mean mass (the outer ones reach to
// infinity); tap j sits at its interval's centroid under the mean marginal (so the mean kernel's first moment, how
// far light bleeds, is kept; u K0(u) integrates to 1 - u K1(u)) and weighs, per band, C over its interval: the
// weights of a band sum to 1 exactly.
#pragma once
#include <vector>

#include "lucent/scene.h"
#include "methods/screen_space/screen_space_io.h"
#include "methods/screen_space/screen_space_profile_io.h"

namespace lucent::methods::screen_space {

// H(v) = integral over [0, v] of the normalised marginal in u = s x of `profile` (LUCENT_SCREEN_SPACE_PROFILE_*;
// v >= 0; H(inf) = 1/2).
double marginal_half_cdf(int profile, double v);
// integral over [0, v] of u times the normalised marginal in u (v >= 0, may be infinite: Burley's 10 / (4 pi)).
double marginal_half_moment(int profile, double v);
// The scale s [1/length] per band of a material's profile, from its coefficients in 1/length
// (shader::burley_scale).
glm::dvec3 band_scales(const glm::vec3& sigma_a, const glm::vec3& sigma_s, const glm::vec3& g, float eta);
// The taps of one material (coefficients in 1/scene unit): offsets in scene units.
std::vector<shader::ScreenSpaceTapGPU> kernel_taps(const glm::vec3& sigma_a, const glm::vec3& sigma_s,
                                                   const glm::vec3& g, float eta, int taps, int profile);
// Every translucent object's material in the order of the scene's material buffer, `taps` each, padded to
// LUCENT_SCREEN_SPACE_MAX_TAPS per material.
std::vector<shader::ScreenSpaceTapGPU> scene_kernels(const Scene& scene, int taps, int profile);

}  // namespace lucent::methods::screen_space
