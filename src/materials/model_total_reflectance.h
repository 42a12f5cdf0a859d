// model_total_reflectance.h: the flat half-space total diffuse reflectance of a material's diffusion model, the
// number to hold against exact transport (`lucent slab`): light refracted into a semi-infinite medium at one
// point x_i, from a direction at `incidence_deg` to the normal; the fraction of the refracted power that the
// model sends back out through the boundary,
//   total = integral over the plane of S_d(x_i, w_i; x_o) dA(x_o)  x  integral over the hemisphere of
//           T21(w_o) cos(theta_o) dw_o,
// which is how every lucent renderer applies a model (S = T12 S_d T21, the references and the methods alike).
// For the standard dipole the first factor is R_total / pi (its closed form); the directional dipole's S_d carries
// 1 / (4 C_phi(1/eta)), which divides the second factor out again.
#pragma once
#include <glm/glm.hpp>

#include "lucent/material.h"

namespace lucent {

struct ModelTotalReflectance {
  glm::dvec3 total{0.0};          // emergent power per refracted power, per band
  glm::dvec3 radiosity{0.0};      // pi x integral of S_d dA: the scattered radiosity per refracted power
  double exit_transmittance = 0;  // integral of T21 cos dw / pi: the fraction of a diffuse radiance that leaves
};

// Integrates the material's model (material.model, coefficients in mm^-1; the result does not depend on the
// length unit) over the plane: logarithmic rings from 1e-6 mean free paths to 60 diffusion lengths, 256 azimuths
// (one at normal incidence, where every model is rotationally symmetric).
// Accurate to about 1e-4 relative for the three models (checked against the standard dipole's closed form).
ModelTotalReflectance model_total_reflectance(const Material& material, double incidence_deg);

}  // namespace lucent
