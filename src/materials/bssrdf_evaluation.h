// bssrdf_evaluation.h: S_d of a material's diffusion model at one configuration, per colour band, by the same
// header code the shaders compile (bssrdf/model.h); what `lucent bssrdf` prints and lucent.bssrdf() returns.
// Units: positions in mm, coefficients in mm^-1, S_d in mm^-2.
#pragma once
#include <glm/glm.hpp>

#include "lucent/material.h"

namespace lucent {

struct BssrdfEvaluation {
  glm::vec3 S_d{0.0f};  // per band [mm^-2]
  float T12 = 0.0f;     // Fresnel transmittance into the material along w_i
};

// `w_i` (toward the light), `n_i` and `n_o` (the outward normals at the entry and exit points) are unit vectors;
// callers normalise and reject zero vectors.
BssrdfEvaluation evaluate_bssrdf(const Material& material, glm::vec3 x_i, glm::vec3 w_i, glm::vec3 n_i,
                                 glm::vec3 x_o, glm::vec3 n_o);

}  // namespace lucent
