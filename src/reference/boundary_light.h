// boundary_light.h: volpath's next-event estimate at a medium vertex of the lights outside the medium, whose light
// reaches the vertex only through the object's dielectric boundary (docs/references.md, "volpath: delta lights
// behind refracting boundaries").
//
// A directional, point or spot light is a delta, so no sampled direction ever reaches it: the estimate solves for
// the specular chains that connect it to the vertex (shared/specular_chain.h): the light refracts in at an exit
// point e of the chain and reaches x after m internal reflections (m = 0 or 1). Every chain is weighted by the
// exact generalized geometry term of the interpolated-normal surface, which holds the focusing of a curved boundary.
//  - Known chains: Newton's method on the chain's boundary points (e; with a reflection also r), walking across the
//    mesh's edges, from deterministic seeds: where the straight line from x toward the light leaves the object, the
//    rim of the light's silhouette (the caustic behind a convex boundary), each large flat face that faces the light,
//    and for one reflection where the light of each unreflected chain would leave past x. Each solution is made
//    exact from x in the direction parametrization (whose Jacobian is the chain's factor) and counted once.
//  - Every other chain by specular manifold sampling (Zeltner, Georgiev and Jakob 2020): Newton from a random seed on
//    the object's surface finds a chain Z with some probability p_Z; the number of further seeds drawn until Z is
//    found again is geometric with mean 1 / p_Z, so f(Z) times that count is an unbiased estimate of the sum over
//    chains. A known chain found again counts nothing. It runs with a fixed probability (Russian roulette), the
//    reflected chains with one that follows the transmittance to the far side and back, each divided by it.
// At eta = 1 nothing bends the light: the straight ray to the light, through index-matched media, as before.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "reference/integrators.h"

namespace lucent::reference {

// What the estimates cost and found, summed over the calls that pass it (for statistics and tests).
struct BoundaryLightCounts {
  std::int64_t estimates = 0;        // chains asked for (per vertex and light)
  std::int64_t primary_found = 0;    // primary chains found
  std::int64_t evaluations = 0;      // chains evaluated by the solvers on the boundary
  std::int64_t primary_evaluations = 0;  // of which for the unreflected chain from the straight line's exit
  std::int64_t traced = 0;           // rays traced by the solvers and their checks
  std::int64_t projected = 0;        // of which projecting long steps onto the boundary
  std::int64_t polished = 0;         // of which checking and polishing solutions from x
  std::int64_t extra_roots = 0;      // other chains found by manifold sampling
  std::int64_t trials = 0;           // seeds drawn by manifold sampling
  std::int64_t capped = 0;           // counts that reached the trial limit
};

// In-scattered radiance at medium vertex x of `object` (coefficients `k`) toward -path_dir from every light outside
// the medium.
glm::dvec3 light_through_boundary(const ReferenceScene& s, int object, const MediumCoefficients& k, glm::dvec3 x,
                                  glm::dvec3 path_dir, Rng& rng, BoundaryLightCounts* counts = nullptr);

}  // namespace lucent::reference
