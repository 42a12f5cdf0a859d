// model.h: selects the diffusion model S_d per material, one switch shared by C++ and the shaders.
// Adding a model: one header with its S_d, one id here, one case below, one enum value in
// include/lucent/material.h and its name in src/materials/material.cpp (to_string, parse_bssrdf_model).
#ifndef LUCENT_BSSRDF_MODEL_H
#define LUCENT_BSSRDF_MODEL_H
#include "shared/bridge.h"
#include "bssrdf/better_dipole.h"
#include "bssrdf/directional_dipole.h"
#include "bssrdf/multipole_table.h"
#include "bssrdf/photon_beam_diffusion.h"
#include "bssrdf/standard_dipole.h"
#include "bssrdf/tabulated.h"

#define LUCENT_MODEL_STANDARD_DIPOLE 0
#define LUCENT_MODEL_DIRECTIONAL_DIPOLE 1
#define LUCENT_MODEL_PHOTON_BEAM_DIFFUSION 2
#define LUCENT_MODEL_BETTER_DIPOLE 3
#define LUCENT_MODEL_TABULATED 4
#define LUCENT_MODEL_MULTIPOLE 5

LUCENT_SHADER_BEGIN

// S_d [1/length^2] of the selected model for one band. w_i points toward the light. Shaders evaluate the tabulated
// and multipole models only when compiled with LUCENT_TABULATED_MODEL and LUCENT_MULTIPOLE_MODEL
// (render::light_sampling_defines sets them for scenes that use them), so that other scenes' shaders carry no
// table code: with the table code merely present, Mesa llvmpipe 22.3 computed the hybrid method's flat slab 8-18% dark for
// the standard dipole (tests/gl/test_flat_slab.cpp), a miscompilation we did not isolate further. A scene whose
// translucent materials all use one model compiles with LUCENT_SCENE_MODEL, its id: the switch folds to that model
// (on llvmpipe the radiosity-maps integration of the backlit slab took 250-290 ms instead of 460-530 ms with the
// standard dipole, 4 frames at 96x72, the other models' code no longer in the loop).
LUCENT_INLINE float bssrdf_Sd(int model, BandMedium m, float eta, vec3 x_i, vec3 w_i, vec3 n_i, vec3 x_o,
                              vec3 n_o) {
#if defined(LUCENT_SCENE_MODEL)
  model = LUCENT_SCENE_MODEL;
#endif
  if (model == LUCENT_MODEL_STANDARD_DIPOLE) return standard_dipole_Sd(m, eta, x_i, x_o);
  if (model == LUCENT_MODEL_PHOTON_BEAM_DIFFUSION) return photon_beam_diffusion_Sd(m, eta, x_i, x_o);
  if (model == LUCENT_MODEL_BETTER_DIPOLE) return better_dipole_Sd(m, eta, x_i, x_o);
#if !defined(GL_core_profile) || defined(LUCENT_TABULATED_MODEL)
  if (model == LUCENT_MODEL_TABULATED) return tabulated_Sd(m, eta, x_i, w_i, n_i, x_o);
#endif
#if !defined(GL_core_profile) || defined(LUCENT_MULTIPOLE_MODEL)
  if (model == LUCENT_MODEL_MULTIPOLE) return multipole_table_Sd(m, eta, x_i, n_i, x_o, n_o);
#endif
  return directional_dipole_Sd(m, eta, x_i, w_i, n_i, x_o, n_o);
}

// The band medium S_d is evaluated with: make_band_medium's, with the multipole model's slab thickness [length] and
// its table looked up once here rather than per evaluation (a directory search of the table buffer per sample made
// the multipole model's frames 20% longer on llvmpipe).
LUCENT_INLINE BandMedium bssrdf_band_medium(int model, float sigma_a, float sigma_s, float g, float eta, float thickness) {
  BandMedium m = make_band_medium(sigma_a, sigma_s, g);
  m.thickness = thickness;
#if !defined(GL_core_profile) || defined(LUCENT_MULTIPOLE_MODEL)
  if (model == LUCENT_MODEL_MULTIPOLE) m.table = multipole_table_at(bssrdf_table_offset(m.alpha_prime, kMultipoleTableKey, eta));
#endif
  return m;
}

// Radially symmetric diffuse reflectance profile R_d(r) [1/length^2] of the selected model for one band:
// pi S_d on a flat surface lit at normal incidence (x_i at the origin, w_i = n_i = n_o = +z, x_o at distance r
// in the plane), so that S_d ~ R_d(|x_o - x_i|) / pi for every model, exit normalisation included (the multipole
// model's reflectance profile: the light that crosses a thin part is not radial about the entry point). The standard
// dipole's R_d times its exit normalisation; for the directional dipole the dependence on the incident direction
// and the normals is dropped (texture-space methods, which sample by irradiance only, Chang et al. 2008 Eq. 11).
LUCENT_INLINE float bssrdf_radial_Rd(int model, BandMedium m, float eta, float r) {
  if (model == LUCENT_MODEL_STANDARD_DIPOLE) return standard_dipole_Rd(m, eta, r) * standard_dipole_exit_normalization(eta);
  vec3 n = vec3(0.0f, 0.0f, 1.0f);
  return kPi * bssrdf_Sd(model, m, eta, vec3(0.0f), n, n, vec3(r, 0.0f, 0.0f), n);
}

// pi S_d between two surface points without a direction of incidence (w_i = n_i), for methods that carry light
// between points of the surface (local-global's vertices): bssrdf_radial_Rd at their distance, except for the
// multipole model, whose pair of points also says whether the light crossed the part (its reflectance or its
// transmittance, bssrdf/multipole_table.h).
LUCENT_INLINE float bssrdf_pair_Rd(int model, BandMedium m, float eta, vec3 x_i, vec3 n_i, vec3 x_o, vec3 n_o) {
#if !defined(GL_core_profile) || defined(LUCENT_MULTIPOLE_MODEL)
  if (model == LUCENT_MODEL_MULTIPOLE) return kPi * multipole_table_Sd(m, eta, x_i, n_i, x_o, n_o);
#endif
  return bssrdf_radial_Rd(model, m, eta, length(x_o - x_i));
}

LUCENT_SHADER_END

#endif
