// boundary_light.cpp: see boundary_light.h.
#include "reference/boundary_light.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "shared/specular_chain.h"
#include "transport/random_walk.h"

namespace lucent::reference {
namespace {

constexpr int kMaxReflections = 1;        // chains reflected inside more often are not estimated (docs/references.md)
constexpr int kMaxEvaluations = 16;       // chains evaluated per Newton solve on the boundary
constexpr int kMaxPolish = 3;             // Newton steps from x that make a solution exact in its own parametrization
constexpr int kMaxWalkHops = 8;           // triangles one step crosses by walking; a longer step is projected
constexpr double kLongStep = 4.0;       // steps longer than this many triangle sizes are projected, not walked
constexpr double kSurfaceTolerance = 1e-9;    // the miss of x over its distance from the chain's last vertex
constexpr double kDirectionTolerance = 1e-7;  // the angle between the chain's way out and the light's way in
constexpr double kMaxStepOfRadius = 0.25;     // longest step on the boundary, in bounding radii of the object
// Two solutions are one chain when their first vertices seen from x are closer than this many sizes of the
// vertex's triangle (distinct chains come that close only where two merge, at a caustic's fold).
constexpr double kSameChain = 1e-4;
// A solution is confirmed from x when the polished chain's first vertex lies within this many sizes of its triangle
// (or the solve's uncertainty) of the solution's: distinct chains lie triangles apart except at a caustic's fold.
constexpr double kConfirmed = 0.5;
constexpr int kMaxTrials = 1024;          // seeds drawn to find a chain again: (1 - p_Z)^1024 of 1 / p_Z is cut
constexpr int kFacingTries = 8;           // surface samples a seed may take to face the light
// The probability with which a vertex estimates the unreflected chains beyond those its deterministic seeds find, and
// the least with which it estimates the chains reflected once inside (light_through_chains).
constexpr double kOtherChainsProbability = 0.1;
constexpr double kLeastReflectedProbability = 0.05;

// A light as the chains see it.
struct LightTarget {
  bool point = false;
  glm::dvec3 direction{0.0};  // directional: the way the light travels
  glm::dvec3 position{0.0};   // point: where it is
  glm::dvec3 travel_at(const glm::dvec3& y) const { return point ? glm::normalize(y - position) : direction; }
  glm::dvec3 toward_from(const glm::dvec3& x) const { return point ? glm::normalize(position - x) : -direction; }
};

// ---- the object's boundary as the solvers see it --------------------------------------------------------------
struct Triangle {
  glm::dvec3 p[3], n[3];
  glm::dvec3 plane_normal;  // unit, on the side of the corner normals (out of the object)
};

Triangle triangle(const ObjectData& o, int t) {
  const ObjectData::Corners& c = o.corners[static_cast<std::size_t>(t)];
  Triangle tri;
  for (int k = 0; k < 3; ++k) tri.p[k] = glm::dvec3(c.position[k]), tri.n[k] = glm::dvec3(c.normal[k]);
  tri.plane_normal = glm::dvec3(glm::vec3(o.planes[static_cast<std::size_t>(t)]));
  return tri;
}

double triangle_size(const ObjectData& o, int t) { return o.planes[static_cast<std::size_t>(t)].w; }

shader::ChainVertex vertex_at(const Triangle& tri, glm::dvec3 y) {
  return shader::chain_vertex_at(y, tri.p[0], tri.p[1], tri.p[2], tri.n[0], tri.n[1], tri.n[2]);
}

shader::ChainVertex vertex_on_ray(const Triangle& tri, glm::dvec3 origin, glm::dvec3 direction) {
  return shader::chain_vertex_on_triangle(origin, direction, tri.p[0], tri.p[1], tri.p[2], tri.n[0], tri.n[1],
                                          tri.n[2]);
}

struct SurfacePoint {
  int triangle = -1;
  glm::dvec3 position{0.0};
};

// p moved by `delta` (in its triangle's plane) across the mesh; false when the step runs off the mesh's border.
bool walk(const ObjectData& o, SurfacePoint& p, glm::dvec3 delta) {
  for (int hop = 0; hop < kMaxWalkHops; ++hop) {
    const Triangle tri = triangle(o, p.triangle);
    const shader::ChainWalkExit exit = shader::chain_walk_exit(tri.p[0], tri.p[1], tri.p[2], p.position, delta);
    if (exit.edge < 0) {
      p.position += delta;
      return true;
    }
    const int next = o.neighbours[static_cast<std::size_t>(p.triangle)][static_cast<std::size_t>(exit.edge)];
    if (next < 0) return false;
    const glm::dvec3 a = tri.p[exit.edge], b = tri.p[(exit.edge + 1) % 3];
    const glm::dvec3 to_normal(glm::vec3(o.planes[static_cast<std::size_t>(next)]));
    p.position += exit.t * delta;
    delta = shader::chain_unfold((1.0 - exit.t) * delta, a, b, tri.plane_normal, to_normal);
    p.triangle = next;
  }
  return false;
}

// The point p (off the surface after a long step) projected onto the boundary: where the ray from `from` toward it
// meets the object first. Any point of the boundary is a valid iterate; the solution is checked from x at the end.
bool project(const ReferenceScene& s, int object, glm::dvec3 from, glm::dvec3 p, SurfacePoint& out,
             BoundaryLightCounts* counts);

// ---- chains from x (the direction parametrization): the factor and the check ----------------------------------
struct Chain {
  bool valid = false;
  shader::ChainExit exit{};
  shader::ChainConstraint constraint{};
  std::array<glm::dvec3, kMaxReflections + 2> points{};  // x, the reflection vertices, the exit point
  int point_count = 0;
  double exit_offset = 0.0;
};

// The chain leaving x along w, reflected `reflections` times inside, and its constraint toward the light.
Chain trace_chain(const ReferenceScene& s, int object, glm::dvec3 x, glm::dvec3 w, int reflections,
                  const LightTarget& light) {
  const ObjectData& o = s.rt.object(object);
  Chain chain;
  chain.points[0] = x;
  chain.point_count = 1;
  shader::ChainState state = shader::chain_start(x, w);
  double t_min = 0.0;  // x is inside: no offset, a vertex within it of the boundary still finds the boundary
  for (int j = 0; j <= reflections; ++j) {
    const SurfaceHit hit = s.rt.intersect(state.y, state.d, 1e30, t_min);
    if (!hit.hit() || hit.object != object || glm::dot(hit.geometric_normal, state.d) <= 0.0) return chain;
    const shader::ChainVertex v = vertex_on_ray(triangle(o, hit.triangle), state.y, state.d);
    state = shader::chain_advance(state, v);
    chain.points[static_cast<std::size_t>(chain.point_count++)] = state.y;
    if (j < reflections) {
      state = shader::chain_reflect(state, v, o.eta);
      t_min = hit.offset;
      continue;
    }
    chain.exit = shader::chain_refract_out(state, v, o.eta);
    chain.exit_offset = hit.offset;
    chain.constraint = light.point ? shader::chain_constraint_point(chain.exit, light.position)
                                   : shader::chain_constraint_directional(chain.exit, light.direction);
    chain.valid = chain.constraint.refracts;
  }
  return chain;
}

struct Root {
  bool found = false;
  glm::dvec3 w{0.0};
  int reflections = 0;
  Chain chain;
};

// Newton's method from x toward the chain's first vertex: exact in the parametrization whose derivative is the
// chain's factor, and a check that the chain from x really meets the boundary where the solution says.
Root polish(const ReferenceScene& s, int object, glm::dvec3 x, glm::dvec3 w, int reflections, const LightTarget& light,
            BoundaryLightCounts* counts) {
  shader::ChainNewton newton = shader::chain_newton_start();
  glm::dvec3 good = w;
  glm::dvec2 step(0.0);
  for (int i = 0; i < kMaxPolish; ++i) {
    const Chain chain = trace_chain(s, object, x, w, reflections, light);
    if (counts) counts->traced += reflections + 1, counts->polished += reflections + 1;
    newton = shader::chain_newton_judge(newton, chain.valid, glm::length(chain.constraint.residual), kDirectionTolerance);
    if (newton.converged) return {true, w, reflections, chain};
    if (newton.failed) break;
    if (newton.accepted) {
      const shader::ChainStep2 fresh =
          shader::chain_newton_step2(chain.constraint.residual, chain.constraint.j_u, chain.constraint.j_v, 0.1);
      if (!fresh.ok) break;
      good = w, step = fresh.step;
    }
    w = shader::chain_direction_step(good, newton.fraction * step);
  }
  return {};
}

// ---- chains from boundary points (the solvers) --------------------------------------------------------------
// An unreflected chain is a point e of the boundary, where the light refracts in: x must lie on the refracted ray. A
// chain reflected once inside is two points, e and the reflection r: r must lie on the refracted ray from e, and x
// on the ray reflected at r. Both solvers walk their points on the mesh (no ray is traced until a solution is found).

// The light arriving at e, its direction's derivatives along e's step coordinates (a point light's moves with e).
shader::ChainState light_at(const LightTarget& light, glm::dvec3 e, const shader::ChainBasis& basis) {
  const glm::dvec3 travel = light.travel_at(e);
  glm::dvec3 dtravel_u(0.0), dtravel_v(0.0);
  if (light.point) {  // d travel = (I - travel travel^T) d e / |e - light|
    const double r = glm::length(e - light.position);
    dtravel_u = (basis.u - travel * glm::dot(travel, basis.u)) / r;
    dtravel_v = (basis.v - travel * glm::dot(travel, basis.v)) / r;
  }
  return shader::chain_start_at(e, travel, basis.u, basis.v, dtravel_u, dtravel_v);
}

// One evaluation of a solver: validity, the residual's blocks and Jacobian (by the step coordinates of e, then r),
// the relative residual, and the chain's first vertex seen from x.
struct SurfaceEvaluation {
  bool valid = false;
  glm::dvec2 r_a{0.0}, r_b{0.0};
  glm::dvec2 a_e_u{0.0}, a_e_v{0.0}, a_r_u{0.0}, a_r_v{0.0}, b_e_u{0.0}, b_e_v{0.0}, b_r_u{0.0}, b_r_v{0.0};
  double relative = 0.0;
  glm::dvec3 first_vertex{0.0};
  glm::dvec3 arrival{0.0};  // the way the light travels when it reaches x
  int orientation = 0;      // unreflected: the sign of the Jacobian's determinant (0: not taken)
  shader::ChainBasis basis_e{}, basis_r{};
};

SurfaceEvaluation unreflected_chain(const ObjectData& o, const SurfacePoint& e, const LightTarget& light, glm::dvec3 x) {
  SurfaceEvaluation v;
  const Triangle tri = triangle(o, e.triangle);
  v.basis_e = shader::chain_plane_basis(tri.p[0], tri.p[1], tri.p[2]);
  const shader::ChainEntry entry = shader::chain_refract_in(light_at(light, e.position, v.basis_e),
                                                            vertex_at(tri, e.position), o.eta);
  if (!entry.refracts) return v;
  const shader::ChainMiss miss = shader::chain_miss(entry.state, x);
  v.valid = miss.along > 0.0;
  v.r_a = miss.residual, v.a_e_u = miss.j_u, v.a_e_v = miss.j_v;
  v.relative = glm::length(miss.residual) / std::max(miss.distance, 1e-300);
  v.first_vertex = e.position;
  v.arrival = entry.state.d;
  const double det = miss.j_u.x * miss.j_v.y - miss.j_v.x * miss.j_u.y;
  v.orientation = det > 0.0 ? 1 : (det < 0.0 ? -1 : 0);
  return v;
}

SurfaceEvaluation reflected_chain(const ObjectData& o, const SurfacePoint& e, const SurfacePoint& r,
                                  const LightTarget& light, glm::dvec3 x) {
  SurfaceEvaluation v;
  const Triangle tri_e = triangle(o, e.triangle), tri_r = triangle(o, r.triangle);
  v.basis_e = shader::chain_plane_basis(tri_e.p[0], tri_e.p[1], tri_e.p[2]);
  v.basis_r = shader::chain_plane_basis(tri_r.p[0], tri_r.p[1], tri_r.p[2]);
  const shader::ChainEntry entry = shader::chain_refract_in(light_at(light, e.position, v.basis_e),
                                                            vertex_at(tri_e, e.position), o.eta);
  if (!entry.refracts) return v;
  // r on the refracted ray from e: its miss by e's coordinates, and by r's (the miss of a moving point: the state's
  // derivatives of y taken as -dr).
  const shader::ChainMiss a_e = shader::chain_miss(entry.state, r.position);
  const glm::dvec3 zero(0.0);
  const shader::ChainMiss a_r = shader::chain_miss(
      shader::chain_start_at(e.position, entry.state.d, -v.basis_r.u, -v.basis_r.v, zero, zero), r.position);
  // x on the ray reflected at r, of the direction from e to r.
  const glm::dvec3 to_r = r.position - e.position;
  const double length = glm::length(to_r);
  const glm::dvec3 d = to_r / length;
  auto across = [&](glm::dvec3 t) { return (t - d * glm::dot(d, t)) / length; };  // d d for a displacement t of r
  const shader::ChainVertex vertex_r = vertex_at(tri_r, r.position);
  if (!(glm::dot(d, vertex_r.shading_normal) > 0.0)) return v;  // r must be met from inside
  const shader::ChainState by_e = shader::chain_reflect(
      shader::chain_start_at(r.position, d, zero, zero, -across(v.basis_e.u), -across(v.basis_e.v)), vertex_r, o.eta);
  const shader::ChainState by_r = shader::chain_reflect(
      shader::chain_start_at(r.position, d, v.basis_r.u, v.basis_r.v, across(v.basis_r.u), across(v.basis_r.v)),
      vertex_r, o.eta);
  const shader::ChainMiss b_e = shader::chain_miss(by_e, x), b_r = shader::chain_miss(by_r, x);
  v.valid = a_e.along > 0.0 && b_e.along > 0.0;
  v.r_a = a_e.residual, v.r_b = b_e.residual;
  v.a_e_u = a_e.j_u, v.a_e_v = a_e.j_v, v.a_r_u = a_r.j_u, v.a_r_v = a_r.j_v;
  v.b_e_u = b_e.j_u, v.b_e_v = b_e.j_v, v.b_r_u = b_r.j_u, v.b_r_v = b_r.j_v;
  v.relative = glm::length(a_e.residual) / std::max(a_e.distance, 1e-300) +
               glm::length(b_e.residual) / std::max(b_e.distance, 1e-300);
  v.first_vertex = r.position;
  v.arrival = by_e.d;
  return v;
}

// A solution of a boundary solver: the chain's first vertex seen from x (the exit point, or the reflection).
struct SurfaceRoot {
  bool found = false;
  int reflections = 0;
  glm::dvec3 vertex{0.0};
  double size = 0.0;         // of the vertex's triangle
  double uncertainty = 0.0;  // how far the vertex may lie from the exact solution: the Newton step left there [mm]
  SurfacePoint point;        // the exit point e
  glm::dvec3 w{0.0};         // the way the chain leaves x: against the light's last leg (exact however far x is)
  int orientation = 0;       // unreflected: the sign of the Jacobian's determinant (0: not taken)
};

// Two solutions are one chain when their first vertices lie within a small fraction of a triangle, or within what
// their solves leave uncertain (near a caustic the miss at x hardly moves with the vertex, so a converged miss leaves
// the vertex loose: a duplicate counted as a new chain would be weighted by its recount), and, unreflected, turn
// the same way: the two chains that meet at a caustic's fold have Jacobians of opposite sign.
bool same_chain(const SurfaceRoot& a, const SurfaceRoot& b) {
  return a.found && b.found && a.reflections == b.reflections &&
         (a.orientation == 0 || b.orientation == 0 || a.orientation == b.orientation) &&
         glm::length(a.vertex - b.vertex) < std::max(kSameChain * std::max(a.size, b.size),
                                                      4.0 * (a.uncertainty + b.uncertainty));
}

// The length of the Newton step that remains at a converged evaluation, in the plane of the chain's first vertex.
double newton_step_left(const SurfaceEvaluation& v, int reflections) {
  constexpr double kUnbounded = 1e300;
  if (reflections == 0) {
    const shader::ChainStep2 step = shader::chain_newton_step2(v.r_a, v.a_e_u, v.a_e_v, kUnbounded);
    return step.ok ? glm::length(step.step) : 0.0;
  }
  const shader::ChainStep4 step = shader::chain_newton_step4(v.r_a, v.r_b, v.a_e_u, v.a_e_v, v.a_r_u, v.a_r_v, v.b_e_u,
                                                             v.b_e_v, v.b_r_u, v.b_r_v, kUnbounded);
  return step.ok ? glm::length(step.step_q) : 0.0;
}

// The chains found from deterministic seeds (at most kMaxKnownChains, each counted once).
constexpr int kMaxKnownChains = 8;
struct KnownChains {
  std::array<SurfaceRoot, kMaxKnownChains> roots{};
  int count = 0;
  bool contains(const SurfaceRoot& z) const {
    for (int i = 0; i < count; ++i)
      if (same_chain(roots[static_cast<std::size_t>(i)], z)) return true;
    return false;
  }
  void add(const SurfaceRoot& z) {
    if (z.found && !contains(z) && count < kMaxKnownChains) roots[static_cast<std::size_t>(count++)] = z;
  }
};

// Newton's method on the chain's boundary points (e; with a reflection also r), walking on the mesh from the start.
SurfaceRoot solve(const ReferenceScene& s, int object, glm::dvec3 x, SurfacePoint e, SurfacePoint r, int reflections,
                  const LightTarget& light, BoundaryLightCounts* counts) {
  const ObjectData& o = s.rt.object(object);
  const double max_step =
      kMaxStepOfRadius * 0.5 * glm::length(glm::dvec3(o.mesh_upper) - glm::dvec3(o.mesh_lower));
  shader::ChainNewton newton = shader::chain_newton_start();
  SurfacePoint good_e = e, good_r = r;
  shader::ChainBasis basis_e{}, basis_r{};
  glm::dvec2 step_e(0.0), step_r(0.0);
  for (int i = 0; i < kMaxEvaluations; ++i) {
    const SurfaceEvaluation v = reflections == 0 ? unreflected_chain(o, e, light, x) : reflected_chain(o, e, r, light, x);
    if (counts) ++counts->evaluations;
    newton = shader::chain_newton_judge(newton, v.valid, v.relative, kSurfaceTolerance);
    if (newton.converged)
      return {true,
              reflections,
              v.first_vertex,
              triangle_size(o, reflections == 0 ? e.triangle : r.triangle),
              newton_step_left(v, reflections),
              e,
              -glm::normalize(v.arrival),
              v.orientation};
    if (newton.failed) return {};
    if (newton.accepted) {
      good_e = e, good_r = r, basis_e = v.basis_e, basis_r = v.basis_r;
      if (reflections == 0) {
        const shader::ChainStep2 fresh = shader::chain_newton_step2(v.r_a, v.a_e_u, v.a_e_v, max_step);
        if (!fresh.ok) return {};
        step_e = fresh.step;
      } else {
        const shader::ChainStep4 fresh = shader::chain_newton_step4(v.r_a, v.r_b, v.a_e_u, v.a_e_v, v.a_r_u, v.a_r_v,
                                                                   v.b_e_u, v.b_e_v, v.b_r_u, v.b_r_v, max_step);
        if (!fresh.ok) return {};
        step_e = fresh.step_p, step_r = fresh.step_q;
      }
    }
    // The next points: the step from the good ones, walked across the mesh, or projected onto it when long (from x
    // for the chain's first vertex seen from x, from there for the exit point before a reflection); a step that
    // leaves the object is shortened.
    for (;;) {
      const glm::dvec2 de = newton.fraction * step_e, dr = newton.fraction * step_r;
      const glm::dvec3 delta_e = de.x * basis_e.u + de.y * basis_e.v, delta_r = dr.x * basis_r.u + dr.y * basis_r.v;
      e = good_e, r = good_r;
      bool moved = true;
      if (reflections > 0 && (glm::length(delta_r) > kLongStep * triangle_size(o, good_r.triangle) || !walk(o, r, delta_r)))
        moved = project(s, object, x, good_r.position + delta_r, r, counts);
      if (moved && (glm::length(delta_e) > kLongStep * triangle_size(o, good_e.triangle) || !walk(o, e, delta_e)))
        moved = project(s, object, reflections > 0 ? r.position : x, good_e.position + delta_e, e, counts);
      if (moved) break;
      newton = shader::chain_newton_backtrack(newton);
      if (newton.failed) return {};
    }
  }
  return {};
}

bool project(const ReferenceScene& s, int object, glm::dvec3 from, glm::dvec3 p, SurfacePoint& out,
             BoundaryLightCounts* counts) {
  const glm::dvec3 to_p = p - from;
  const double d = glm::length(to_p);
  if (!(d > 0.0)) return false;
  const glm::dvec3 direction = to_p / d;
  const SurfaceHit hit = s.rt.intersect(from, direction, 1e30, EmbreeScene::offset_at(from));
  if (counts) ++counts->traced, ++counts->projected;
  if (!hit.hit() || hit.object != object) return false;
  out = {hit.triangle, vertex_on_ray(triangle(s.rt.object(object), hit.triangle), from, direction).position};
  return true;
}

// ---- the chains of one light ----------------------------------------------------------------------------------
// Where the straight line from x along `direction` leaves the object: the deterministic solves' seeds (toward the
// light: where the unreflected chain leaves; away from it: where light reflected at the far side turns back to x).
bool exit_along(const ReferenceScene& s, int object, glm::dvec3 x, glm::dvec3 direction, SurfacePoint& p,
                BoundaryLightCounts* counts) {
  const SurfaceHit hit = s.rt.intersect(x, direction, 1e30, 0.0);
  if (counts) ++counts->traced;
  if (!hit.hit() || hit.object != object) return false;
  p = {hit.triangle, vertex_on_ray(triangle(s.rt.object(object), hit.triangle), x, direction).position};
  return true;
}

// Where the light refracted into the object at boundary point e meets its boundary again.
bool refracted_exit(const ReferenceScene& s, int object, const SurfacePoint& e, const LightTarget& light,
                    SurfacePoint& r, BoundaryLightCounts* counts) {
  const ObjectData& o = s.rt.object(object);
  const Triangle tri = triangle(o, e.triangle);
  const shader::ChainBasis basis = shader::chain_plane_basis(tri.p[0], tri.p[1], tri.p[2]);
  const shader::ChainEntry entry =
      shader::chain_refract_in(light_at(light, e.position, basis), vertex_at(tri, e.position), o.eta);
  if (!entry.refracts) return false;
  const glm::dvec3 d = glm::normalize(entry.state.d);
  const SurfaceHit hit = s.rt.intersect(e.position, d, 1e30, EmbreeScene::offset_at(e.position));
  if (counts) ++counts->traced;
  if (!hit.hit() || hit.object != object) return false;
  r = {hit.triangle, vertex_on_ray(triangle(o, hit.triangle), e.position, d).position};
  return true;
}

SurfacePoint random_point(const ReferenceScene& s, int object, Rng& rng) {
  const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const SurfaceSample p = s.rt.sample_surface(object, u0, u1, u2, u3);
  return {p.triangle, p.position};
}

// A random seed: e uniform over the object's surface among the points that face the light (the first of a few draws
// that does), and with a reflection r where the light refracted at e meets the boundary again. Every chain's points have a neighbourhood of seeds that Newton takes to it, so every
// chain is found with a positive probability.
SurfaceRoot sampled_chain(const ReferenceScene& s, int object, glm::dvec3 x, int reflections,
                          const LightTarget& light, Rng& rng, BoundaryLightCounts* counts) {
  if (counts) ++counts->trials;
  const ObjectData& o = s.rt.object(object);
  SurfacePoint e;
  bool facing = false;
  for (int i = 0; i < kFacingTries && !facing; ++i) {
    e = random_point(s, object, rng);
    facing = glm::dot(vertex_at(triangle(o, e.triangle), e.position).shading_normal, light.travel_at(e.position)) < 0.0;
  }
  if (!facing) return {};
  SurfacePoint r;
  if (reflections > 0 && !refracted_exit(s, object, e, light, r, counts)) return {};
  return solve(s, object, x, e, r, reflections, light, counts);
}

// The light a found chain brings to x, scattered toward -path_dir: the light's radiance times the chain's factor,
// the way outside (index-matched media attenuate it, anything else blocks it), the medium along the chain and the
// phase function.
glm::dvec3 chain_light(const ReferenceScene& s, int object, const MediumCoefficients& k, glm::dvec3 path_dir,
                       const Root& root, const LightTarget& light, const glm::dvec3& light_radiance,
                       const PointLight* point_light, Rng& rng) {
  const ObjectData& o = s.rt.object(object);
  const Chain& chain = root.chain;
  const double factor = shader::chain_radiance_factor(chain.exit, chain.constraint, o.eta);
  if (!(factor > 0.0) || !std::isfinite(factor)) return glm::dvec3(0.0);
  const glm::dvec3 e = chain.exit.e;
  const glm::dvec3 travel = light.travel_at(e);
  const glm::dvec3 e_outside = e - 2.0 * chain.exit_offset * travel;
  glm::dvec3 radiance = light_radiance;
  double t_max = 1e30;
  if (point_light) {
    const double r = glm::length(light.position - e);
    radiance = point_light_intensity(s, *point_light, travel) / (r * r);
    t_max = glm::length(light.position - e_outside) - EmbreeScene::offset_at(light.position);
  }
  const glm::dvec3 outside = shadow_transmittance(s, e_outside, -travel, t_max, rng);
  if (glm::all(glm::lessThanEqual(outside, glm::dvec3(0.0)))) return glm::dvec3(0.0);
  glm::dvec3 inside(1.0);
  if (o.heterogeneous()) {
    for (int i = 0; i + 1 < chain.point_count; ++i)
      inside *= medium_transmittance(o, k, chain.points[static_cast<std::size_t>(i)],
                                     chain.points[static_cast<std::size_t>(i + 1)], rng);
  } else {
    inside = glm::exp(-k.sigma_t() * chain.exit.path_length);
  }
  // The light arrives at x travelling along -w.
  const glm::dvec3 phase = henyey_greenstein_pdf_bands(glm::dot(root.w, path_dir), o.g);
  return radiance * factor * outside * inside * phase;
}

// The light of a solution, once it is made exact from x (polish, from the way the solution's light arrives): 0 when
// the chain from x does not confirm it, i.e. meets the boundary first elsewhere (a part of the object between x and the
// solution) or converges to another chain (counted as itself already).
glm::dvec3 root_light(const ReferenceScene& s, int object, const MediumCoefficients& k, glm::dvec3 x,
                      glm::dvec3 path_dir, const SurfaceRoot& z, const LightTarget& light,
                      const glm::dvec3& light_radiance, const PointLight* point_light, Rng& rng,
                      BoundaryLightCounts* counts) {
  const Root root = polish(s, object, x, z.w, z.reflections, light, counts);
  if (!root.found) return glm::dvec3(0.0);
  const double confirmed = std::max(kConfirmed * z.size, 4.0 * z.uncertainty);
  if (glm::length(root.chain.points[1] - z.vertex) > confirmed) return glm::dvec3(0.0);
  return chain_light(s, object, k, path_dir, root, light, light_radiance, point_light, rng);
}

// The sum over the chains with `reflections` internal reflections other than the known ones, by specular manifold
// sampling: the number of trials until a found chain is found again has mean 1 / p_Z.
glm::dvec3 other_chains(const ReferenceScene& s, int object, const MediumCoefficients& k, glm::dvec3 x,
                        glm::dvec3 path_dir, int reflections, const KnownChains& known, const LightTarget& light,
                        const glm::dvec3& light_radiance, const PointLight* point_light, Rng& rng,
                        BoundaryLightCounts* counts) {
  const SurfaceRoot z = sampled_chain(s, object, x, reflections, light, rng, counts);
  if (!z.found || known.contains(z)) return glm::dvec3(0.0);
  if (counts) ++counts->extra_roots;
  int trials = 1;
  for (; trials < kMaxTrials; ++trials)
    if (same_chain(sampled_chain(s, object, x, reflections, light, rng, counts), z)) break;
  if (trials == kMaxTrials && counts) ++counts->capped;
  return static_cast<double>(trials) *
         root_light(s, object, k, x, path_dir, z, light, light_radiance, point_light, rng, counts);
}

// The rim seed: behind a convex boundary the light's grazing rays are refracted most and cross the others, so in the
// caustic near the far side a second unreflected chain enters close to the light's silhouette, on the side of the
// primary chain's exit point e. The seed extrapolates there from e along the circle of e's curvature in the plane of
// e's normal and the light (to the point where the light meets the boundary at cos_i = kRimCosine), and takes the
// point where the light's ray toward it meets the object.
constexpr double kRimCosine = 0.12;

bool rim_seed(const ReferenceScene& s, int object, glm::dvec3 x, const SurfacePoint& primary, const LightTarget& light,
              SurfacePoint& e, BoundaryLightCounts* counts) {
  const ObjectData& o = s.rt.object(object);
  const shader::ChainVertex v = vertex_at(triangle(o, primary.triangle), primary.position);
  const glm::dvec3 travel = light.travel_at(primary.position), n = v.shading_normal;
  glm::dvec3 side = n - glm::dot(n, travel) * travel;  // across the light, toward e's side
  const double side_length = glm::length(side);
  if (!(side_length > 1e-9)) return false;
  side /= side_length;
  // The curvature along the boundary's direction toward the silhouette (the light's tangential part).
  glm::dvec3 tangent = travel - glm::dot(travel, n) * n;
  if (!(glm::length(tangent) > 1e-9)) return false;
  tangent = glm::normalize(tangent);
  const double curvature = glm::length(shader::chain_normal_change(v, tangent));
  if (!(curvature > 0.0)) return false;
  const glm::dvec3 centre = primary.position - n / curvature;
  if (!(glm::dot(x - centre, travel) > 0.0)) return false;  // x before the centre of curvature: no caustic there
  const glm::dvec3 n_rim = -kRimCosine * travel + std::sqrt(1.0 - kRimCosine * kRimCosine) * side;
  const glm::dvec3 target = centre + n_rim / curvature;
  const double reach = 2.0 * glm::length(glm::dvec3(o.mesh_upper) - glm::dvec3(o.mesh_lower));
  const glm::dvec3 origin = light.point ? light.position : target - reach * travel;
  const glm::dvec3 direction = glm::normalize(target - origin);
  const SurfaceHit hit = s.rt.intersect(origin, direction, 1e30, -1.0);
  if (counts) ++counts->traced;
  if (!hit.hit() || hit.object != object || glm::dot(hit.geometric_normal, direction) >= 0.0) return false;
  e = {hit.triangle, vertex_on_ray(triangle(o, hit.triangle), origin, direction).position};
  return true;
}

// The sum over the chains with `reflections` internal reflections: those `known` (found from the deterministic seeds),
// and, with probability `others`, every other by manifold sampling.
glm::dvec3 chains_of(const ReferenceScene& s, int object, const MediumCoefficients& k, glm::dvec3 x,
                     glm::dvec3 path_dir, int reflections, const KnownChains& known, double others,
                     const LightTarget& light, const glm::dvec3& light_radiance, const PointLight* point_light,
                     Rng& rng, BoundaryLightCounts* counts) {
  glm::dvec3 L(0.0);
  for (int i = 0; i < known.count; ++i)
    L += root_light(s, object, k, x, path_dir, known.roots[static_cast<std::size_t>(i)], light, light_radiance,
                    point_light, rng, counts);
  if (rng.uniform() < others)
    L += other_chains(s, object, k, x, path_dir, reflections, known, light, light_radiance, point_light, rng, counts) /
         others;
  return L;
}

// The seed of a large flat face that faces the light: where the light refracted by that face, traced back from x,
// meets the object; a seed only when that point is on the face (the face's chain then needs no Newton step for a
// directional light).
bool face_seed(const ReferenceScene& s, int object, glm::dvec3 x, int face, const LightTarget& light, SurfacePoint& e,
               BoundaryLightCounts* counts) {
  const ObjectData& o = s.rt.object(object);
  const glm::dvec3 n(o.faces.patches[static_cast<std::size_t>(face)].normal);
  const glm::dvec3 travel = light.travel_at(x);
  if (!(glm::dot(n, travel) < 0.0)) return false;
  const double cos_i = -glm::dot(travel, n);
  const double cos_t = std::sqrt(std::max(0.0, 1.0 - (1.0 - cos_i * cos_i) / (o.eta * o.eta)));
  const glm::dvec3 inside = glm::normalize(travel / o.eta + (cos_i / o.eta - cos_t) * n);
  return exit_along(s, object, x, -inside, e, counts) &&
         o.faces.patch_of[static_cast<std::size_t>(e.triangle)] == face;
}

// Every chain of one light. The deterministic seeds of unreflected chains: e where the straight line from x toward
// the light leaves the object, the rim seed, and each large flat face's seed; of chains reflected once, each of their
// solutions' e (or the straight line's, where there is none) with r where the light that arrives along it would go on
// past x, and on flat faces with r on each other face where that light reflected there would reach x. Manifold sampling of the other chains
// runs with a fixed probability, and the chains reflected once with one that follows the transmittance from x to
// where the first solution's light would leave past x and back (Russian roulette, unbiased): light reflected at the
// far side is worth its cost near that side.
glm::dvec3 light_through_chains(const ReferenceScene& s, int object, const MediumCoefficients& k, glm::dvec3 x,
                                glm::dvec3 path_dir, const LightTarget& light, const glm::dvec3& light_radiance,
                                const PointLight* point_light, Rng& rng, BoundaryLightCounts* counts) {
  if (counts) ++counts->estimates;
  const ObjectData& o = s.rt.object(object);
  SurfacePoint toward, seed;
  const bool has_toward = exit_along(s, object, x, light.toward_from(x), toward, counts);
  KnownChains unreflected;
  if (has_toward) {
    const std::int64_t before = counts ? counts->evaluations : 0;
    unreflected.add(solve(s, object, x, toward, SurfacePoint{}, 0, light, counts));
    if (counts) counts->primary_evaluations += counts->evaluations - before;
    if (counts && unreflected.count > 0) ++counts->primary_found;
  }
  if (unreflected.count > 0 && rim_seed(s, object, x, unreflected.roots[0].point, light, seed, counts))
    unreflected.add(solve(s, object, x, seed, SurfacePoint{}, 0, light, counts));
  for (int face = 0; face < static_cast<int>(o.faces.patches.size()); ++face)
    if (face_seed(s, object, x, face, light, seed, counts))
      unreflected.add(solve(s, object, x, seed, SurfacePoint{}, 0, light, counts));
  glm::dvec3 L = chains_of(s, object, k, x, path_dir, 0, unreflected, kOtherChainsProbability, light, light_radiance,
                           point_light, rng, counts);
  if (!has_toward) return L;

  // The entries of reflected chains: each unreflected solution's exit point with the way its light goes inside (or,
  // where none was found, the straight line's exit with the light's way), and where that light would leave past x.
  struct Entry {
    SurfacePoint e;
    glm::dvec3 w;
  };
  std::array<Entry, kMaxKnownChains> entries;
  const int entry_count = std::max(1, unreflected.count);
  for (int i = 0; i < entry_count; ++i) {
    const SurfacePoint e = unreflected.count > 0 ? unreflected.roots[static_cast<std::size_t>(i)].point : toward;
    entries[static_cast<std::size_t>(i)] = {e, unreflected.count > 0 ? glm::normalize(x - e.position) : -light.toward_from(x)};
  }
  std::array<SurfacePoint, kMaxKnownChains> beyond;
  std::array<bool, kMaxKnownChains> has_beyond{};
  auto past_x = [&](int i) {
    has_beyond[static_cast<std::size_t>(i)] =
        exit_along(s, object, x, entries[static_cast<std::size_t>(i)].w, beyond[static_cast<std::size_t>(i)], counts);
  };
  past_x(0);
  const glm::dvec3 sigma_t = k.sigma_t();
  const double back_and_forth =
      has_beyond[0] ? 2.0 * std::min({sigma_t.x, sigma_t.y, sigma_t.z}) * glm::length(beyond[0].position - x) : 0.0;
  const double reflected = std::clamp(std::exp(-back_and_forth), kLeastReflectedProbability, 1.0);
  if (rng.uniform() < reflected) {
    KnownChains once;
    for (int i = 0; i < entry_count; ++i) {
      const SurfacePoint& e = entries[static_cast<std::size_t>(i)].e;
      const glm::dvec3 w = entries[static_cast<std::size_t>(i)].w;
      if (i > 0) past_x(i);
      if (has_beyond[static_cast<std::size_t>(i)])
        once.add(solve(s, object, x, e, beyond[static_cast<std::size_t>(i)], 1, light, counts));
      // Light that entered through a flat face and reflected off another flat face: r where the reflected light,
      // traced back from x, meets the object (on that face).
      const int entry_face = o.faces.patch_of[static_cast<std::size_t>(e.triangle)];
      if (entry_face < 0) continue;
      for (int face = 0; face < static_cast<int>(o.faces.patches.size()) && once.count < kMaxKnownChains; ++face) {
        const glm::dvec3 n(o.faces.patches[static_cast<std::size_t>(face)].normal);
        if (face == entry_face || !(glm::dot(w, n) > 0.0)) continue;
        SurfacePoint r;
        if (exit_along(s, object, x, -(w - 2.0 * glm::dot(w, n) * n), r, counts) &&
            o.faces.patch_of[static_cast<std::size_t>(r.triangle)] == face)
          once.add(solve(s, object, x, e, r, 1, light, counts));
      }
    }
    L += chains_of(s, object, k, x, path_dir, 1, once, kOtherChainsProbability, light, light_radiance, point_light,
                   rng, counts) /
         reflected;
  }
  return L;
}

// eta = 1: the light goes straight through the boundary; the straight ray toward it, through index-matched media.
glm::dvec3 light_straight(const ReferenceScene& s, int object, const MediumCoefficients& k, glm::dvec3 x,
                          glm::dvec3 path_dir, const LightTarget& light, const glm::dvec3& light_radiance,
                          const PointLight* point_light, Rng& rng) {
  const ObjectData& o = s.rt.object(object);
  const glm::dvec3 toward = light.toward_from(x);
  const SurfaceHit hit = s.rt.intersect(x, toward, 1e30, 0.0);
  if (!hit.hit() || hit.object != object) return glm::dvec3(0.0);
  const glm::dvec3 travel = -toward;
  if (glm::dot(hit.normal, travel) >= 0.0) return glm::dvec3(0.0);  // the boundary faces away from the light
  const glm::dvec3 entry_outside = hit.position - 2.0 * hit.offset * travel;
  glm::dvec3 radiance = light_radiance;
  double t_max = 1e30;
  if (point_light) {
    const double r = glm::length(light.position - x);
    radiance = point_light_intensity(s, *point_light, travel) / (r * r);
    t_max = glm::length(light.position - entry_outside) - EmbreeScene::offset_at(light.position);
  }
  const glm::dvec3 outside = shadow_transmittance(s, entry_outside, -travel, t_max, rng);
  if (glm::all(glm::lessThanEqual(outside, glm::dvec3(0.0)))) return glm::dvec3(0.0);
  const glm::dvec3 phase = henyey_greenstein_pdf_bands(glm::dot(travel, -path_dir), o.g);
  return radiance * outside * medium_transmittance(o, k, hit.position, x, rng) * phase;
}

}  // namespace

glm::dvec3 light_through_boundary(const ReferenceScene& s, int object, const MediumCoefficients& k, glm::dvec3 x,
                                  glm::dvec3 path_dir, Rng& rng, BoundaryLightCounts* counts) {
  const ObjectData& o = s.rt.object(object);
  glm::dvec3 L(0.0);
  auto one_light = [&](const LightTarget& light, const glm::dvec3& radiance, const PointLight* point_light) {
    if (o.eta == 1.0) return light_straight(s, object, k, x, path_dir, light, radiance, point_light, rng);
    return light_through_chains(s, object, k, x, path_dir, light, radiance, point_light, rng, counts);
  };
  for (const DirectionalLight& light : s.scene.lights) {
    LightTarget target;
    target.direction = glm::normalize(glm::dvec3(light.direction));
    L += one_light(target, glm::dvec3(light.radiance), nullptr);
  }
  for (std::size_t i = 0; i < s.scene.point_lights.size(); ++i) {
    if (s.rt.medium_of_point_light(i) >= 0) continue;  // inside a medium: volpath connects it inside
    const PointLight& light = s.scene.point_lights[i];
    LightTarget target;
    target.point = true;
    target.position = glm::dvec3(light.position);
    L += one_light(target, glm::dvec3(0.0), &light);
  }
  return L;
}

}  // namespace lucent::reference
