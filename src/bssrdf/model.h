// model.h: selects the diffusion model S_d per material, one switch shared by C++ and the shaders.
// Adding a model: one header with its S_d, one id here, one case below, one enum value in
// include/lucent/material.h and its name in src/materials/material.cpp (to_string, parse_bssrdf_model).
#ifndef LUCENT_BSSRDF_MODEL_H
#define LUCENT_BSSRDF_MODEL_H
#include "shared/bridge.h"
#include "bssrdf/better_dipole.h"
#include "bssrdf/directional_dipole.h"
#include "bssrdf/photon_beam_diffusion.h"
#include "bssrdf/standard_dipole.h"
#include "bssrdf/tabulated.h"

#define LUCENT_MODEL_STANDARD_DIPOLE 0
#define LUCENT_MODEL_DIRECTIONAL_DIPOLE 1
#define LUCENT_MODEL_PHOTON_BEAM_DIFFUSION 2
#define LUCENT_MODEL_BETTER_DIPOLE 3
#define LUCENT_MODEL_TABULATED 4

LUCENT_SHADER_BEGIN

// S_d [1/length^2] of the selected model for one band. w_i points toward the light. Shaders evaluate the tabulated
// model only when compiled with LUCENT_TABULATED_MODEL (render::light_sampling_defines sets it for scenes that use
// it): with the table code merely present, Mesa llvmpipe 22.3 computed the hybrid method's flat slab 8-18% dark for
// the standard dipole (tests/gl/test_flat_slab.cpp), a miscompilation we did not isolate further.
LUCENT_INLINE float bssrdf_Sd(int model, BandMedium m, float eta, vec3 x_i, vec3 w_i, vec3 n_i, vec3 x_o,
                              vec3 n_o) {
  if (model == LUCENT_MODEL_STANDARD_DIPOLE) return standard_dipole_Sd(m, eta, x_i, x_o);
  if (model == LUCENT_MODEL_PHOTON_BEAM_DIFFUSION) return photon_beam_diffusion_Sd(m, eta, x_i, x_o);
  if (model == LUCENT_MODEL_BETTER_DIPOLE) return better_dipole_Sd(m, eta, x_i, x_o);
#if !defined(GL_core_profile) || defined(LUCENT_TABULATED_MODEL)
  if (model == LUCENT_MODEL_TABULATED) return tabulated_Sd(m, eta, x_i, w_i, n_i, x_o);
#endif
  return directional_dipole_Sd(m, eta, x_i, w_i, n_i, x_o, n_o);
}

// Radially symmetric diffuse reflectance profile R_d(r) [1/length^2] of the selected model for one band:
// pi S_d on a flat surface lit at normal incidence (x_i at the origin, w_i = n_i = n_o = +z, x_o at distance r
// in the plane), so that S_d ~ R_d(|x_o - x_i|) / pi for every model, exit normalisation included. The standard
// dipole's R_d times its exit normalisation; for the directional dipole the dependence on the incident direction
// and the normals is dropped (texture-space methods, which sample by irradiance only, Chang et al. 2008 Eq. 11).
LUCENT_INLINE float bssrdf_radial_Rd(int model, BandMedium m, float eta, float r) {
  if (model == LUCENT_MODEL_STANDARD_DIPOLE) return standard_dipole_Rd(m, eta, r) * standard_dipole_exit_normalization(eta);
  vec3 n = vec3(0.0f, 0.0f, 1.0f);
  return kPi * bssrdf_Sd(model, m, eta, vec3(0.0f), n, n, vec3(r, 0.0f, 0.0f), n);
}

LUCENT_SHADER_END

#endif
