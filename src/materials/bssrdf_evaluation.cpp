// bssrdf_evaluation.cpp: one S_d evaluation per band through the shared model headers.
#include "materials/bssrdf_evaluation.h"

#include "bssrdf/model.h"

namespace lucent {

BssrdfEvaluation evaluate_bssrdf(const Material& material, glm::vec3 x_i, glm::vec3 w_i, glm::vec3 n_i,
                                 glm::vec3 x_o, glm::vec3 n_o) {
  BssrdfEvaluation result;
  for (int band = 0; band < 3; ++band) {
    shader::BandMedium medium =
        shader::make_band_medium(material.sigma_a[band], material.sigma_s[band], material.g[band]);
    medium.thickness = material.thickness_mm;
    result.S_d[band] =
        shader::bssrdf_Sd(static_cast<int>(material.model), medium, material.eta, x_i, w_i, n_i, x_o, n_o);
  }
  result.T12 = shader::fresnel_transmittance(material.eta, glm::dot(w_i, n_i));
  return result;
}

}  // namespace lucent
