// random_walk.h (photon transport, in lucent_core): the physics of the CPU references inside a homogeneous medium and at its smooth dielectric
// boundary: free-flight distances, Henyey-Greenstein scattering, Fresnel reflection and refraction with total
// internal reflection, and the Russian roulette that keeps weights unbiased. Shared by `lucent slab` and the
// volumetric path tracer. Fresnel comes from the same header the shaders use (bssrdf/fresnel.h).
#pragma once
#include <glm/glm.hpp>

#include "transport/rng.h"

namespace lucent::reference {

// Distance to the next interaction, exponential with rate sigma_t.
double sample_free_flight(Rng& rng, double sigma_t);

// New direction after Henyey-Greenstein scattering of `direction` with mean cosine g (pbrt-v4 convention:
// g > 0 scatters forward).
glm::dvec3 sample_henyey_greenstein(Rng& rng, const glm::dvec3& direction, double g);
double henyey_greenstein_pdf(double cos_theta, double g);  // [1/sr], cos_theta between old and new directions
// The same per band, for per-band asymmetries g.
glm::dvec3 henyey_greenstein_pdf_bands(double cos_theta, const glm::dvec3& g);

// Fresnel reflectance for light travelling in `direction` that meets a boundary with unit normal `normal`
// (either orientation) passing from relative index 1 into eta_ratio = n_other_side / n_this_side.
double dielectric_reflectance(const glm::dvec3& direction, const glm::dvec3& normal, double eta_ratio);
glm::dvec3 reflect(const glm::dvec3& direction, const glm::dvec3& normal);
// Refracted direction; requires no total internal reflection (dielectric_reflectance < 1).
glm::dvec3 refract(const glm::dvec3& direction, const glm::dvec3& normal, double eta_ratio);

// Russian roulette on a path weight: below `threshold`, survive with probability `survival` and divide the
// weight by it (unbiased), else return false (terminated).
bool russian_roulette(Rng& rng, double& weight, double threshold = 1e-3, double survival = 0.1);

// An orthonormal frame around unit w.
void orthonormal_basis(const glm::dvec3& w, glm::dvec3& u, glm::dvec3& v);

}  // namespace lucent::reference
