// integrators.h: the two CPU ground truths, radiance along one camera ray.
//
// volpath (the physics): brute-force volumetric path tracing. Translucent interiors are homogeneous media
// (sigma_a, sigma_s, per-band Henyey-Greenstein g) behind a smooth dielectric boundary (Fresnel reflection and
// refraction, total internal reflection, eta); opaque objects are Lambertian with full global illumination.
// Directional and point lights are deltas, so light reaches a medium vertex only along specular chains through the
// boundary: next-event estimation solves for them (Newton's method on the chain, every refracted path and those
// reflected once inside, with the exact focusing of the curved boundary; boundary_light.h) and weights each by its
// Fresnel terms, its generalized geometry term and the attenuation to the vertex.
// A point light inside a medium (EmbreeScene::medium_of_point_light) is connected to that medium's vertices
// straight through it, unless the boundary is in between. Russian roulette keeps it unbiased.
// Heterogeneous media (a material's "field", media/heterogeneous_field.h): free flights by delta tracking against
// the majorant max m sigma_t with null collisions, and the next-event segments' transmittance by ratio tracking;
// both unbiased (volpath.cpp).
// Sphere jumps (ReferenceScene::sphere_jumps): deep inside a homogeneous medium a path crosses the largest sphere
// that fits there in one step, a pre-computed walk (shared/sphere_walk.h) weighted for absorption and the other
// bands, with the collisions' next-event estimates represented by one of them; unbiased (docs/references.md).
// Known limits: light reflected twice or more inside the boundary before it first scatters, and light that leaves
// the object and enters it again (a concave part's light through another part), are not estimated; nested or
// touching translucent objects are not supported.
//
// bssrdf (the model; homogeneous only: a material's field is ignored, as by the diffusion models): Monte Carlo
// integration of Dal Corso et al.'s eq. 1 over the object's surface with the
// same S_d code the shaders run, light visibility by shadow rays, Fresnel transmittance in and out. x_i comes
// from uniform area sampling combined by multiple importance sampling with exponential probes around x_o (the
// paper's reference uses area sampling with a Russian roulette on exp(-sigma_tr r); that misses the directional
// dipole's near-field peak too often to converge in useful time, see bssrdf_integrator.cpp). Opaque objects get
// direct light plus the light emerging from the translucent objects (one area sample of a translucent surface
// with a shadow ray and a nested estimate of its B), as the real-time method's VPLs carry it; no other bounces.
//
// Both: camera rays that miss show the background radiance; rays that escape later carry nothing (the
// background does not light the scene, as in the real-time methods).
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "lucent/scene.h"
#include "reference/embree_scene.h"
#include "transport/rng.h"
#include "transport/sphere_jump_bank.h"

namespace lucent::reference {

struct ReferenceScene {
  const Scene& scene;
  const EmbreeScene& rt;
  int max_scatter = 0;  // volpath: scattering events per path at most (0: unlimited; ReferenceSettings)
  // volpath: sphere jumps (shared/sphere_walk.h; docs/references.md, "Sphere jumps") where a path scatters deep
  // inside a homogeneous medium whose bands share one g, and max_scatter is 0. They draw from `jump_bank`: without
  // one, paths step through every collision.
  bool sphere_jumps = true;
  const SphereJumpBank* jump_bank = nullptr;
};

// What a path tells besides its radiance, and the sample index it belongs to.
struct PathRecord {
  int sample = 0;           // the sample index (selects the sphere-jump bank)
  std::int64_t steps = 0;   // out: volpath's walk steps: free flights in media, tentative collisions, sphere jumps
};

// `first_hit`, when given, is the hit of the ray (origin, direction) already traced: a pixel's camera rays through
// its centre all share it, so the renderer traces it once per pixel instead of once per sample. `record`, when
// given, passes the sample index in and the path's statistics out.
glm::dvec3 volpath_radiance(const ReferenceScene& s, glm::dvec3 origin, glm::dvec3 direction, Rng& rng,
                            const SurfaceHit* first_hit = nullptr, PathRecord* record = nullptr);
glm::dvec3 bssrdf_radiance(const ReferenceScene& s, glm::dvec3 origin, glm::dvec3 direction, Rng& rng,
                           const SurfaceHit* first_hit = nullptr, PathRecord* record = nullptr);

// A point or spot light's intensity toward `direction` (unit, from the light), in scene units (E = I / d^2).
glm::dvec3 point_light_intensity(const ReferenceScene& s, const PointLight& light, glm::dvec3 direction);

// Direct light on an opaque Lambertian surface point (shadow rays to every light). With `rng` (volpath),
// index-matched media on a shadow ray attenuate it (shadow_transmittance); without (bssrdf, which models
// translucent objects by their surface, as the real-time methods do), every surface blocks it.
glm::dvec3 direct_light_lambertian(const ReferenceScene& s, const SurfaceHit& hit, glm::dvec3 normal,
                                   Rng* rng = nullptr);

// volpath: the transmittance of the straight shadow ray from `origin` (outside every medium) along `direction`
// up to t_max. Opaque surfaces and refracting (eta != 1) boundaries block it; an index-matched medium (eta = 1:
// the ray goes straight through its boundary) attenuates it by its transmittance between the points where the
// ray enters and leaves it (exact when homogeneous, ratio tracking when heterogeneous).
glm::dvec3 shadow_transmittance(const ReferenceScene& s, glm::dvec3 origin, glm::dvec3 direction, double t_max,
                                Rng& rng);

// volpath: the transmittance between a and b inside object o whose homogeneous coefficients are `k` (the material's,
// or a textured material's at the point the path entered): exact when homogeneous, ratio tracking when
// heterogeneous (unbiased, in [0, 1]).
glm::dvec3 medium_transmittance(const ObjectData& o, const MediumCoefficients& k, glm::dvec3 a, glm::dvec3 b,
                                Rng& rng);

}  // namespace lucent::reference
