// radiosity_maps.h: directional subsurface scattering cached in scattered-radiosity maps.
//
// Dal Corso, Frisvad, Mosegaard, Baerentzen, "Interactive Directional Subsurface Scattering and Transport of
// Emergent Light", The Visual Computer 2016 (Sections 3-3.2, Fig. 3, Algorithm 1):
//   1. light G-buffer: one orthographic layer per directional light, layered rendering;
//   2. K scattered-radiosity maps from orthographic views placed by a Halton sequence on the bounding sphere,
//      B(x_o) by Monte Carlo (eq. 9) with N samples per band from p_exp (eqs. 10-12), in a compute shader;
//      accumulated over frames while only the camera moves; mipmapped for noise filtering;
//   3. combine: Algorithm 1 per pixel and L_o = F_t B / pi (eq. 5).
// Converged mode (Section 3.2, converged_after): once the maps have accumulated enough frames and only the
// camera moves, only step 3 runs.
// Shaders: shaders/gbuffer/, src/methods/radiosity_maps/shaders/. Design notes: docs/methods/radiosity-maps.md.
#pragma once
#include <vector>

#include <glm/glm.hpp>

namespace lucent::methods {

// The unit directions d_k of the K map views (Halton bases 2 and 3 mapped uniformly onto the sphere).
std::vector<glm::vec3> halton_sphere_directions(int count);
// A spherical Fibonacci set: more even than Halton points for small K.
std::vector<glm::vec3> fibonacci_sphere_directions(int count);

}  // namespace lucent::methods
