// volpath.cpp: the physics reference (see integrators.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include "reference/boundary_light.h"
#include "reference/integrators.h"
#include "shared/sphere_walk.h"
#include "transport/random_walk.h"

namespace lucent::reference {
namespace {

constexpr int kMaxSurfaceBounces = 64;
constexpr int kRouletteAfter = 8;
constexpr int kMaxShadowCrossings = 64;  // index-matched media a shadow ray crosses at most

double mean(const glm::dvec3& v) { return (v.x + v.y + v.z) / 3.0; }
double max_component(const glm::dvec3& v) { return std::max({v.x, v.y, v.z}); }

glm::dvec3 exp_neg(const glm::dvec3& v) { return glm::dvec3(std::exp(-v.x), std::exp(-v.y), std::exp(-v.z)); }

}  // namespace

// Exact in a homogeneous medium; in a heterogeneous one, ratio tracking (Novak et al. 2014): tentative points at the
// rate mu of the largest band majorant, each multiplying band k by 1 - sigma_t,k(x) / mu. Unbiased, and in [0, 1]
// because mu >= sigma_t.
glm::dvec3 medium_transmittance(const ObjectData& o, const MediumCoefficients& k, glm::dvec3 a, glm::dvec3 b,
                                Rng& rng) {
  const double length = glm::length(b - a);
  if (!o.heterogeneous()) return exp_neg(k.sigma_t() * length);
  const double mu = max_component(o.majorant);
  const glm::dvec3 direction = (b - a) / std::max(length, 1e-300), sigma_t = o.sigma_a + o.sigma_s;
  glm::dvec3 T(1.0);
  for (double t = -std::log(1.0 - rng.uniform()) / mu; t < length; t -= std::log(1.0 - rng.uniform()) / mu) {
    T *= glm::max(glm::dvec3(0.0), 1.0 - o.multiplier(a + t * direction) * sigma_t / mu);
    if (max_component(T) <= 0.0) break;
  }
  return T;
}

// Index-matched media on a shadow ray attenuate it: nothing bends the ray at their boundaries, so the light
// crosses them along the same straight line. (Stopping at every surface lost the light through a bunny's front
// ear to the back one and through its head to its neck: 1.5% of the image, found against Blender Cycles.)
glm::dvec3 shadow_transmittance(const ReferenceScene& s, glm::dvec3 origin, glm::dvec3 direction, double t_max,
                                Rng& rng) {
  glm::dvec3 T(1.0);
  for (int crossing = 0; crossing < kMaxShadowCrossings; ++crossing) {
    const SurfaceHit enter = s.rt.intersect(origin, direction, t_max);
    if (!enter.hit()) return T;
    const ObjectData& o = s.rt.object(enter.object);
    if (!o.translucent || o.eta != 1.0) return glm::dvec3(0.0);
    // The far side: the next surface must be the same object's (nested or touching media are not supported).
    const SurfaceHit leave = s.rt.intersect(enter.position, direction, t_max - enter.t);
    if (!leave.hit() || leave.object != enter.object) return glm::dvec3(0.0);
    T *= medium_transmittance(o, o.medium_at(enter.uv), enter.position, leave.position, rng);
    if (max_component(T) <= 0.0) return T;
    origin = leave.position;
    t_max -= enter.t + leave.t;
  }
  return glm::dvec3(0.0);
}

namespace {

// Next-event estimation at a medium scattering vertex: light in-scattered toward -path_dir, through the medium
// `k` of the path, from every light outside the medium through the boundary (boundary_light.h). The point lights
// inside the medium are estimated along the flights instead (interior_lights_along).
glm::dvec3 medium_next_event(const ReferenceScene& s, int object, const MediumCoefficients& k, glm::dvec3 x,
                             glm::dvec3 path_dir, const Rng& path_rng) {
  // Its own random numbers: the path's do not depend on how many the estimate draws.
  Rng rng = path_rng.split();
  return light_through_boundary(s, object, k, x, path_dir, rng);
}

bool has_interior_lights(const ReferenceScene& s, int object) {
  for (std::size_t i = 0; i < s.scene.point_lights.size(); ++i)
    if (s.rt.medium_of_point_light(i) == object) return true;
  return false;
}


// Chromatic media: distances and phase directions are sampled with one "hero" band per path; every band keeps
// its throughput divided by the hero's path pdf (throughput) and the ratio of its own path pdf to the hero's
// (r_u). Contributions are throughput / mean(r_u): the balance heuristic over bands for the whole path
// (Wilkie et al. 2014; pbrt-v4's rescaled path probabilities). Per-event MIS instead lets one band's weight
// grow as a product over hundreds of scattering events in high-albedo media (coloured fireflies).
struct PathState {
  glm::dvec3 origin, direction;
  glm::dvec3 throughput{1.0};
  glm::dvec3 r_u{1.0};
  glm::dvec3 radiance{0.0};
  int hero = 0;
  int medium = -1;  // object whose interior the path is in
  // Its coefficients: the material's, or a textured material's where the path entered it (each walk inside is
  // one homogeneous medium, as in Cycles' random-walk subsurface scattering; docs/materials.md, "Textures").
  MediumCoefficients medium_k;
  int events = 0;
  int scatterings = 0;  // medium scattering events so far
  std::int64_t steps = 0;  // free flights in media, tentative collisions of delta tracking, sphere jumps
  // Sphere jumps: the bank's sample index, the first record this path uses and how many it used (records
  // jump_start, jump_start + 1, ... of a bank, never one twice), and what the last distance query found.
  int sample = 0;
  int jump_start = 0, jumps_used = 0;
  bool distance_known = false;
  glm::dvec3 distance_origin{0.0};
  double distance = 0.0, distance_upper = 0.0;  // at distance_origin: no surface nearer; one at most this far
  glm::dvec3 weight() const { return throughput / mean(r_u); }
  void add(const glm::dvec3& incoming) { radiance += weight() * incoming; }
};

bool roulette(PathState& p, Rng& rng) {
  if (++p.events < kRouletteAfter) return true;
  // Only paths whose weight fell below 1 play: survival = weight, so survivors continue with weight 1. (Capping
  // survival at 0.95 for all paths made long paths' weights grow as 1.05^events: heavy-tailed fireflies.)
  double survive = std::min(1.0, max_component(p.weight()));
  if (survive >= 1.0) return true;
  if (survive <= 0.0 || rng.uniform() >= survive) return false;
  p.throughput /= survive;
  return true;
}

// At the boundary from inside: relative index 1/eta; reflect with probability F (1 under total internal
// reflection), else refract out.
bool leave_or_reflect(const ReferenceScene& s, PathState& p, Rng& rng, const SurfaceHit& boundary) {
  const ObjectData& o = s.rt.object(p.medium);
  glm::dvec3 n = boundary.normal;
  double F = dielectric_reflectance(p.direction, n, 1.0 / o.eta);
  p.origin = boundary.position;
  if (rng.uniform() < F) {
    p.direction = reflect(p.direction, n);
    p.origin -= boundary.offset * boundary.geometric_normal;
  } else {
    p.direction = refract(p.direction, n, 1.0 / o.eta);
    p.throughput *= o.eta * o.eta;  // radiance leaving the denser medium: L_out = L_in / eta^2 seen backward
    p.origin += boundary.offset * boundary.geometric_normal;
    p.medium = -1;
  }
  return roulette(p, rng);
}

// A conservative lower bound on the distance from x to every surface, for the sphere jump's levels: balls of
// doubling radius from `too_small` (the smallest level's) up to `radius`, each asked only whether some surface lies
// within it, until one does (a ball's emptiness is all a level needs, and a fine mesh answers that far faster than
// the nearest point: the 10 mm sphere of 262,144 triangles spent 37 of 42 s in nearest-point queries). Distances
// are 1-Lipschitz: from the last query at x0, what was known there bounds d(x) within |x - x0|, which can decide
// without a query (a known empty ball that still covers the levels, or a surface too near for any).
double surface_distance_bound(const ReferenceScene& s, PathState& p, glm::dvec3 x, double radius, double too_small) {
  double empty = 0.0, upper = std::numeric_limits<double>::infinity();
  if (p.distance_known) {
    const double moved = glm::length(x - p.distance_origin);
    empty = std::max(0.0, p.distance - moved);
    upper = p.distance_upper + moved;
    if (upper < too_small) return empty;
  }
  for (double r = too_small; r <= radius * (1.0 + 1e-9); r *= 2.0) {
    const double ball = r * (1.0 + 2e-5);  // a level of radius r fits with the caller's margin of 1e-5
    if (ball <= empty) continue;
    double found = 0.0;
    if (s.rt.surface_within(x, ball, found)) {
      upper = std::min(upper, found);
      break;
    }
    empty = ball;
  }
  p.distance = empty, p.distance_upper = upper;
  p.distance_origin = x;
  p.distance_known = true;
  return empty;
}

// The light of the point lights inside the path's medium in-scattered along the flight about to leave p.origin in
// p.direction, up to the boundary at t_b, toward -p.direction: per light one point of the flight sampled with
// density proportional to 1 / |x(t) - light|^2 (equiangular sampling, Kulla and Fajardo 2012), then straight to
// the light when no boundary is in between (a concave medium's light behind a fold is not estimated, as for thin
// parts). Next-event estimation at the scattering vertices would estimate the same integral (a vertex falls on the
// flight with density T sigma_t and weighs sigma_s / sigma_t), but with 1/r^2 itself: infinite variance where
// paths pass near the light. Sphere jumps skip media with such lights (a jump has no flights to sample).
glm::dvec3 interior_lights_along(const ReferenceScene& s, const PathState& p, double t_b, Rng& rng) {
  const ObjectData& o = s.rt.object(p.medium);
  glm::dvec3 L(0.0);
  for (std::size_t i = 0; i < s.scene.point_lights.size(); ++i) {
    if (s.rt.medium_of_point_light(i) != p.medium) continue;
    const PointLight& light = s.scene.point_lights[i];
    const glm::dvec3 x_l(light.position);
    const double delta = glm::dot(x_l - p.origin, p.direction);  // the flight's point nearest the light
    const double h = glm::length(x_l - (p.origin + delta * p.direction));
    if (!(h > 0.0)) continue;  // the light on the flight's line: a set of measure zero
    const double theta_a = std::atan(-delta / h), theta_b = std::atan((t_b - delta) / h);
    if (!(theta_b > theta_a)) continue;
    const double t = delta + h * std::tan(theta_a + rng.uniform() * (theta_b - theta_a));
    const double pdf = h / ((theta_b - theta_a) * (h * h + (t - delta) * (t - delta)));
    const glm::dvec3 x = p.origin + t * p.direction;
    const glm::dvec3 to_light = x_l - x;
    const double d = glm::length(to_light);
    if (!(d > 0.0) || s.rt.intersect(x, to_light / d, d, 0.0).hit()) continue;
    const glm::dvec3 light_dir = -to_light / d;  // the way the light travels
    const glm::dvec3 sigma_s = o.heterogeneous() ? std::min(o.multiplier(x), 1.0) * o.sigma_s : p.medium_k.sigma_s;
    const glm::dvec3 phase = henyey_greenstein_pdf_bands(glm::dot(light_dir, -p.direction), o.g);
    L += medium_transmittance(o, p.medium_k, p.origin, x, rng) * sigma_s * phase *
         point_light_intensity(s, light, light_dir) / (d * d) * medium_transmittance(o, p.medium_k, x_l, x, rng) / pdf;
  }
  return L;
}

// A sphere jump at scattering vertex x (its next-event estimate done): the walk from x to the boundary of the
// largest sphere about x inside the medium, from a bank record (shared/sphere_walk.h; docs/references.md, "Sphere
// jumps"). False, and nothing changed, where no jump applies: the caller steps as usual.
bool sphere_jump(const ReferenceScene& s, PathState& p, Rng& rng, glm::dvec3 x) {
  if (!s.sphere_jumps || !s.jump_bank || s.max_scatter > 0 || has_interior_lights(s, p.medium)) return false;
  const ObjectData& o = s.rt.object(p.medium);
  if (o.heterogeneous() || o.g.x != o.g.y || o.g.x != o.g.z) return false;
  const glm::dvec3 sigma_t = p.medium_k.sigma_t();
  const double sigma_t_hero = sigma_t[p.hero];
  if (!(sigma_t_hero > 0.0)) return false;
  using shader::kSphereJumpLevelCount;
  // No point inside a closed mesh is farther from it than half its box's smallest side (the surface is crossed both
  // ways along that axis): the distance query needs no larger radius, and none where the smallest sphere is larger.
  const glm::dvec3 extent = glm::dvec3(o.mesh_upper) - glm::dvec3(o.mesh_lower);
  const double room = 0.5 * std::min({extent.x, extent.y, extent.z});
  const double largest = std::min(shader::sphere_jump_level_radius(kSphereJumpLevelCount - 1) / sigma_t_hero, room);
  const double smallest = shader::sphere_jump_level_radius(0) / sigma_t_hero;
  if (smallest > largest) return false;
  const double bound = surface_distance_bound(s, p, x, largest, smallest);
  int level = -1;
  // (A margin of 1e-5 for the float rounding of the records' points.) A level is skipped once the path has made
  // as many jumps as it has records: the records jump_start + k (mod its size) of the jumps k made there stay
  // distinct.
  for (int l = 0; l < kSphereJumpLevelCount; ++l)
    if (shader::sphere_jump_level_radius(l) <= (1.0 - 1e-5) * bound * sigma_t_hero &&
        p.jumps_used < s.jump_bank->record_count(l))
      level = l;
  if (level < 0) return false;

  // The first direction, as a scattering event would sample it, and the record's frame: +z to it, a uniform
  // azimuth about it.
  const double g = o.g[p.hero];
  const glm::dvec3 w = sample_henyey_greenstein(rng, p.direction, g);
  glm::dvec3 u, v;
  orthonormal_basis(w, u, v);
  const double phi = 2.0 * M_PI * rng.uniform();
  const glm::dvec3 a = std::cos(phi) * u + std::sin(phi) * v, b = -std::sin(phi) * u + std::cos(phi) * v;
  auto rotate = [&](const glm::vec4& c) { return double(c.x) * a + double(c.y) * b + double(c.z) * w; };
  const std::span<const shader::SphereWalkGPU> bank = s.jump_bank->records(p.sample, static_cast<float>(g), level);
  const shader::SphereWalkGPU& r =
      bank[static_cast<std::size_t>((p.jump_start + p.jumps_used) % static_cast<int>(bank.size()))];
  ++p.jumps_used;
  ++p.steps;
  const double radius = shader::sphere_jump_level_radius(level) / sigma_t_hero;  // [scene units]
  const glm::vec3 sigma_s_f(p.medium_k.sigma_s), sigma_t_f(sigma_t);
  const float st_h = static_cast<float>(sigma_t_hero);
  // The collisions inside: each would have added its next-event estimate; n times the one at a uniformly picked
  // collision estimates their sum.
  const float n = r.exit_dir.w;
  if (n >= 1.0f) {
    const float j = r.vertex_dir.w, length_v = r.vertex.w / st_h;
    const glm::dvec3 throughput_v =
        p.throughput * glm::dvec3(shader::sphere_jump_throughput(j, length_v, sigma_s_f, sigma_t_f, st_h));
    const glm::dvec3 r_u_v = p.r_u * glm::dvec3(shader::sphere_jump_ratio(j, length_v, sigma_t_f, st_h));
    const glm::dvec3 vertex = x + radius * rotate(r.vertex), incoming = glm::normalize(rotate(r.vertex_dir));
    p.radiance += static_cast<double>(n) * (throughput_v / mean(r_u_v)) *
                  medium_next_event(s, p.medium, p.medium_k, vertex, incoming, rng);
  }
  const float length = r.exit.w / st_h;
  p.throughput *= glm::dvec3(shader::sphere_jump_throughput(n, length, sigma_s_f, sigma_t_f, st_h));
  p.r_u *= glm::dvec3(shader::sphere_jump_ratio(n, length, sigma_t_f, st_h));
  // From the sphere's boundary (or the walk's last collision) the path goes on with a fresh free flight.
  p.origin = x + radius * rotate(r.exit);
  p.direction = glm::normalize(rotate(r.exit_dir));
  return true;
}

// A scattering vertex at x, reached with the throughput update already applied: next-event estimation, then a
// new direction from the hero band's phase function (or a sphere jump).
bool scatter(const ReferenceScene& s, PathState& p, Rng& rng, glm::dvec3 x) {
  const ObjectData& o = s.rt.object(p.medium);
  p.add(medium_next_event(s, p.medium, p.medium_k, x, p.direction, rng));
  if (s.max_scatter > 0 && ++p.scatterings >= s.max_scatter) return false;
  if (sphere_jump(s, p, rng, x)) return roulette(p, rng);
  glm::dvec3 next = sample_henyey_greenstein(rng, p.direction, o.g[p.hero]);
  glm::dvec3 phase = henyey_greenstein_pdf_bands(glm::dot(next, p.direction), o.g);
  p.throughput *= phase / phase[p.hero];
  p.r_u *= phase / phase[p.hero];
  p.origin = x, p.direction = next;
  return roulette(p, rng);
}

// Heterogeneous medium: delta tracking against the band majorants sigma_maj = max m sigma_t, sampled with the
// hero's, with null collisions (pbrt-v4's spectral formulation of Miller et al. 2019: at a tentative point the
// hero chooses absorption, scattering or a null collision with probabilities sigma_a, sigma_s, sigma_n over its
// majorant, and every band carries T_maj sigma_{s|n} over the hero's pdf in throughput and r_u). A scattering
// vertex is returned in x.
enum class Flight { Scattered, Absorbed, ReachedBoundary };
Flight delta_track(const ReferenceScene& s, PathState& p, Rng& rng, double boundary_t, glm::dvec3& x) {
  const ObjectData& o = s.rt.object(p.medium);
  const glm::dvec3 sigma_maj = o.majorant, sigma_t = o.sigma_a + o.sigma_s;
  const double mu = sigma_maj[p.hero];
  double t = 0.0;
  for (;;) {
    const double dt = -std::log(1.0 - rng.uniform()) / mu;
    if (t + dt >= boundary_t) {
      const glm::dvec3 T = exp_neg(sigma_maj * (boundary_t - t));
      p.throughput *= T / T[p.hero];
      p.r_u *= T / T[p.hero];
      return Flight::ReachedBoundary;
    }
    t += dt;
    ++p.steps;  // each tentative collision is a step (the walk on the GPU counts them the same way)
    x = p.origin + t * p.direction;
    const double m = o.multiplier(x);
    const glm::dvec3 sigma_t_x = m * sigma_t, sigma_s_x = std::min(m, 1.0) * o.sigma_s;
    const glm::dvec3 sigma_a_x = sigma_t_x - sigma_s_x;
    const glm::dvec3 sigma_n = glm::max(glm::dvec3(0.0), sigma_maj - sigma_t_x);
    const glm::dvec3 T = exp_neg(sigma_maj * dt);
    const double u = rng.uniform() * mu;
    if (u < sigma_a_x[p.hero]) return Flight::Absorbed;
    if (u < sigma_a_x[p.hero] + sigma_s_x[p.hero]) {
      const double pdf = T[p.hero] * sigma_s_x[p.hero];
      p.throughput *= T * sigma_s_x / pdf;
      p.r_u *= T * sigma_s_x / pdf;
      return Flight::Scattered;
    }
    const double pdf = T[p.hero] * sigma_n[p.hero];
    if (!(pdf > 0.0)) return Flight::Absorbed;
    p.throughput *= T * sigma_n / pdf;
    p.r_u *= T * sigma_n / pdf;
    if (max_component(p.throughput) <= 0.0) return Flight::Absorbed;
  }
}

// Inside a medium: scatter (with next-event estimation) or reach the boundary and reflect or leave.
bool medium_step(const ReferenceScene& s, PathState& p, Rng& rng) {
  const ObjectData& o = s.rt.object(p.medium);
  const glm::dvec3 sigma_t = p.medium_k.sigma_t();
  ++p.steps;
  // The point lights inside the medium, along this flight (as the next-event estimate at its end would count them:
  // not past the last scattering event allowed).
  if ((s.max_scatter == 0 || p.scatterings < s.max_scatter) && has_interior_lights(s, p.medium)) {
    const SurfaceHit boundary = s.rt.intersect(p.origin, p.direction, 1e30, 0.0);
    if (boundary.hit()) {
      Rng own = rng.split();  // its own random numbers, as the next-event estimates'
      p.add(interior_lights_along(s, p, boundary.t, own));
    }
  }
  // Medium rays start inside (scattering vertices, or boundary points offset inward): no epsilon skip, so a vertex
  // within epsilon of the boundary still finds it.
  if (o.heterogeneous()) {
    SurfaceHit boundary = s.rt.intersect(p.origin, p.direction, 1e30, 0.0);
    if (!boundary.hit()) return false;  // numerical leak out of a closed mesh
    glm::dvec3 x;
    switch (delta_track(s, p, rng, boundary.t, x)) {
      case Flight::Absorbed: return false;
      case Flight::Scattered: return scatter(s, p, rng, x);
      case Flight::ReachedBoundary: return leave_or_reflect(s, p, rng, boundary);
    }
  }
  // The free flight first, then the boundary searched only up to it: in a dense medium most flights end long
  // before the boundary, and a ray limited to the flight visits few BVH nodes.
  double t = -std::log(1.0 - rng.uniform()) / sigma_t[p.hero];
  SurfaceHit boundary = s.rt.intersect(p.origin, p.direction, t, 0.0);
  if (!boundary.hit()) {
    // A numerical leak (a vertex that escaped a closed mesh, or t infinite in a band without extinction) ends
    // the path once the vertex would leave the mesh's bounds.
    const glm::dvec3 x = p.origin + t * p.direction;
    if (!std::isfinite(t) || glm::any(glm::lessThan(x, glm::dvec3(o.mesh_lower))) ||
        glm::any(glm::greaterThan(x, glm::dvec3(o.mesh_upper))))
      return false;
    // Scattering vertex: distance pdf sigma_t e^{-sigma_t t} of each band relative to the hero's.
    glm::dvec3 attenuation = exp_neg(sigma_t * t);
    glm::dvec3 pdf = sigma_t * attenuation;
    p.throughput *= p.medium_k.sigma_s * attenuation / pdf[p.hero];
    p.r_u *= pdf / pdf[p.hero];
    return scatter(s, p, rng, x);
  }
  // Past the boundary: probability e^{-sigma_t t_b} of each band relative to the hero's.
  glm::dvec3 attenuation = exp_neg(sigma_t * boundary.t);
  p.throughput *= attenuation / attenuation[p.hero];
  p.r_u *= attenuation / attenuation[p.hero];
  return leave_or_reflect(s, p, rng, boundary);
}

// Outside: hit a surface; opaque = Lambertian with next-event estimation, translucent = dielectric boundary.
bool surface_step(const ReferenceScene& s, PathState& p, Rng& rng, int bounce, const SurfaceHit* known_hit) {
  const SurfaceHit hit = known_hit ? *known_hit : s.rt.intersect(p.origin, p.direction);
  if (!hit.hit()) {
    if (bounce == 0) p.add(glm::dvec3(s.scene.render.background));
    return false;
  }
  const ObjectData& o = s.rt.object(hit.object);
  glm::dvec3 n = hit.normal, ng = hit.geometric_normal;
  if (!o.translucent) {
    if (glm::dot(n, p.direction) > 0.0) n = -n, ng = -ng;
    p.add(direct_light_lambertian(s, hit, n, &rng));
    glm::dvec3 u, v;
    orthonormal_basis(n, u, v);
    double r = std::sqrt(rng.uniform()), phi = 2.0 * M_PI * rng.uniform();
    p.direction = r * std::cos(phi) * u + r * std::sin(phi) * v + std::sqrt(std::max(0.0, 1.0 - r * r)) * n;
    p.origin = hit.position + hit.offset * ng;
    p.throughput *= o.albedo;  // cosine sampling cancels cos/pi
    return roulette(p, rng);
  }
  if (glm::dot(ng, p.direction) > 0.0) return false;  // reached an inside face from outside: leaky mesh
  double F = dielectric_reflectance(p.direction, n, o.eta);
  if (rng.uniform() < F) {
    p.direction = reflect(p.direction, n);
    p.origin = hit.position + hit.offset * ng;
  } else {
    p.direction = refract(p.direction, n, o.eta);
    p.throughput /= o.eta * o.eta;
    p.origin = hit.position - hit.offset * ng;
    p.medium = hit.object;
    p.medium_k = o.medium_at(hit.uv);
  }
  return true;
}

}  // namespace

glm::dvec3 volpath_radiance(const ReferenceScene& s, glm::dvec3 origin, glm::dvec3 direction, Rng& rng,
                            const SurfaceHit* first_hit, PathRecord* record) {
  PathState p;
  p.origin = origin, p.direction = direction;
  p.hero = std::min(2, static_cast<int>(rng.uniform() * 3.0));
  if (record) p.sample = record->sample;
  if (s.sphere_jumps && s.jump_bank) {
    const int records = s.jump_bank->record_count(0);
    p.jump_start = std::min(records - 1, static_cast<int>(rng.uniform() * records));
  }
  int bounce = 0;
  while (bounce < kMaxSurfaceBounces) {
    const SurfaceHit* known = bounce == 0 ? first_hit : nullptr;
    bool alive = p.medium >= 0 ? medium_step(s, p, rng) : surface_step(s, p, rng, bounce++, known);
    if (!alive) break;
  }
  if (record) record->steps = p.steps;
  return p.radiance;
}

}  // namespace lucent::reference
