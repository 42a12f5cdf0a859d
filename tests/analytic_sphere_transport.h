// analytic_sphere_transport.h: an independent estimate of the radiance of a homogeneous sphere behind a refracting
// boundary, lit by one directional light, for checking volpath where the boundary curves. It shares no code with
// lucent's estimators: the sphere is exact (no mesh), and next-event estimation enumerates every refracted path from
// the light to a medium vertex in closed form instead of solving for one.
//
// Why that is possible: a ray entering a sphere stays in the plane through the centre that holds its direction and
// entry point, so every path the light takes to a vertex x (refracted in, reflected m times inside) lies in the plane
// spanned by the light's axis (its direction; for a point light the line from it through the centre) and x. In that
// plane the rays form a one-parameter family, the signed impact parameter b in (-R, R); the m-th leg of ray b passes
// x where the signed distance g_m(b) of x from its line is 0. The roots are bracketed on a grid in b (denser toward
// |b| = R, where rays graze) and refined by bisection. Each root delivers the fluence E T prod F |b| / (rho |d g_m /
// d b|) e^{-sigma_t L}: the power E |b| db dphi through an annulus of the light's beam spread over the ray tube's
// cross-section at x, |d g / d b| db in the plane times rho dphi across it (rho: x's distance from the axis). A point
// light of intensity I at distance D from the centre sends its ray of impact parameter b at the angle alpha =
// asin(b / D) from the axis, I sin(alpha) d alpha dphi into it: the fluence I T prod F |b| / (rho |d g_m / d b| D^2
// cos(alpha)) e^{-sigma_t L} (E |b| with E = I / D^2 as D grows).
//
// The camera path is an ordinary volumetric path tracer of the sphere (Fresnel reflection and refraction, total
// internal reflection, Henyey-Greenstein scattering); escaping paths carry nothing (a black background).
#pragma once
#include <glm/glm.hpp>

#include "transport/rng.h"

namespace lucent::test {

struct AnalyticSphere {
  double radius = 1.0;                           // centred at the origin [mm]
  double sigma_s = 1.0, sigma_a = 0.01, g = 0.0;  // [1/mm]
  double eta = 1.4;
  glm::dvec3 light_direction{1.0, 0.0, 0.0};  // the way the light travels (unit); a point light's, at the centre
  double irradiance = 1.0;                      // on a surface facing the light; a point light's intensity
  double point_distance = 0.0;                  // > radius: a point light this far from the centre, against its way
  int max_reflections = 3;                      // internal reflections of the light before a vertex, at most
  int grid = 256;                               // bracketing grid over the impact parameter
};

// In-scattered radiance at medium point x toward -path_dir (path_dir: the camera path's direction arriving at x)
// from every path of the light to x, the phase function included.
// by_reflections, when given, receives the part of each number of reflections (max_reflections + 1 values).
double analytic_sphere_next_event(const AnalyticSphere& sphere, const glm::dvec3& x, const glm::dvec3& path_dir,
                                  double* by_reflections = nullptr);

// Radiance along a camera ray from outside the sphere.
double analytic_sphere_radiance(const AnalyticSphere& sphere, glm::dvec3 origin, glm::dvec3 direction,
                                reference::Rng& rng);

}  // namespace lucent::test
