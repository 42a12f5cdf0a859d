// boundary_light.glsl: the walk's next-event estimate of the lights outside a medium, whose light reaches a medium
// vertex only through the object's dielectric boundary: volpath's estimator (reference/boundary_light.h; the chain
// math in shared/specular_chain.h, the same code in float), with the walk's traversal and its loop budget.
//  - Newton's method on the chain's boundary points (the exit point e; with one internal reflection also the
//    reflection r), walking across the mesh's edges (the triangles' neighbours) or projecting long steps by one ray,
//    from deterministic seeds: where the straight line from x toward the light leaves the object, the rim of the
//    light's silhouette (the caustic behind a convex boundary), and with a reflection where the line away from the
//    light leaves;
//  - each solution made exact from x in the direction parametrization, whose Jacobian is the chain's factor;
//  - every other chain by specular manifold sampling, under Russian roulette that follows the transmittance toward
//    the light.
// Included by trace.comp after its rays, media and lights (trace, offset_at, eta_of, sigma_t_of, transmittance,
// shadow_transmittance, point_intensity, rnd, loop_count).

layout(std430, binding = LUCENT_BINDING_WALK_NEIGHBOURS) readonly buffer NeighbourBlock { ivec4 neighbours[]; };
layout(std430, binding = LUCENT_BINDING_WALK_AREAS) readonly buffer AreaBlock { vec2 surface_cdf[]; };
layout(std430, binding = LUCENT_BINDING_WALK_FACES) readonly buffer FaceBlock { vec4 flat_faces[]; };

// In float: a solution is converged when x misses it by this fraction of its distance, or the chain's way out
// misses the light by this angle; two solutions are one chain within a hundredth of a triangle, float rounding, or
// what their solves leave uncertain.
const int kChainMaxEvaluations = 16;
const int kChainMaxPolish = 3;
// A step is walked across the mesh (no ray) up to 64 triangle sizes and 64 edge crossings, projected by a ray beyond
// (volpath walks 4 and 8): a walk costs a few loop iterations, a ray a traversal (rays per estimate on the marble
// bunny 5.9 -> 3.7; the roots are the same, only the way to them differs).
const int kChainMaxWalkHops = 64;
const float kChainLongStep = 64.0f;
const float kChainSurfaceTolerance = 2e-6f;
const float kChainDirectionTolerance = 2e-5f;
const float kChainMaxStepOfRadius = 0.25f;
const float kChainRounding = 4.0f;  // the floors of those tolerances, in self-intersection offsets (offset_at)
const float kChainSame = 1e-2f;
const float kChainConfirmed = 0.5f;
const int kChainMaxTrials = 128;  // seeds drawn to find a chain again, at most (the CPU's 1024: docs/references.md)
// Loop iterations one recount may take, at most, then cut like one that reaches kChainMaxTrials: a constant, so that
// a path's estimate does not depend on how the frame's work was split into dispatches. (It was a quarter of the
// dispatch's loop budget: renders at budgets 1023, 4095 and 16383 then differed in 10 of the potato bunny's 5184
// paths, 48 x 36 x 3 frames, and the default budget's image mean was 0.56% below the uncut recount's; with 16384 the
// three budgets give the same image bit for bit, 2 paths are cut, the mean 0.006% below. Without the cut the loop
// cap fired 9 times at the default budget: a replay repeats such an event, but one alone past the cap is dropped.)
const uint kChainRecountLoops = 16384u;
const int kChainFacingTries = 8;
const float kChainOtherProbability = 0.1f;
const float kChainLeastReflectedProbability = 0.05f;
const float kChainRimCosine = 0.12f;

struct LightTarget {
  bool point;
  vec3 direction;  // directional: the way the light travels
  vec3 position;   // point: where it is
};
vec3 light_travel_at(LightTarget light, vec3 y) { return light.point ? normalize(y - light.position) : light.direction; }
vec3 light_toward_from(LightTarget light, vec3 x) { return light.point ? normalize(light.position - x) : -light.direction; }

// ---- the object's boundary ----------------------------------------------------------------------------------
struct ChainTriangle {
  vec3 p0, p1, p2, n0, n1, n2;
  vec3 plane_normal;  // unit, on the side of the corner normals
  float size;         // the square root of its area
};

ChainTriangle chain_triangle(int t) {
  TriangleGPU g = triangles[t];
  ChainTriangle tri;
  tri.p0 = g.p0.xyz, tri.p1 = g.p0.xyz + g.e1.xyz, tri.p2 = g.p0.xyz + g.e2.xyz;
  tri.n0 = g.n0.xyz, tri.n1 = g.n1.xyz, tri.n2 = g.n2.xyz;
  vec3 c = cross(g.e1.xyz, g.e2.xyz);
  float area2 = length(c);
  tri.plane_normal = c / max(area2, 1e-30f);
  if (dot(tri.plane_normal, tri.n0 + tri.n1 + tri.n2) < 0.0f) tri.plane_normal = -tri.plane_normal;
  tri.size = sqrt(0.5f * area2);
  return tri;
}

ChainVertex vertex_at(ChainTriangle tri, vec3 y) { return chain_vertex_at(y, tri.p0, tri.p1, tri.p2, tri.n0, tri.n1, tri.n2); }
ChainVertex vertex_on_ray(ChainTriangle tri, vec3 o, vec3 d) {
  return chain_vertex_on_triangle(o, d, tri.p0, tri.p1, tri.p2, tri.n0, tri.n1, tri.n2);
}

struct SurfacePoint {
  int triangle;
  vec3 position;
};

// p moved by `delta` (in its triangle's plane) across the mesh; false when it runs off the border or too far.
bool walk(inout SurfacePoint p, vec3 delta) {
  // loop bound: checked; kChainMaxWalkHops (64) (each iteration counted in loop_count, budgeted by random_walk.cpp)
  for (int hop = 0; hop < kChainMaxWalkHops; ++hop) {
    ++loop_count;
    ChainTriangle tri = chain_triangle(p.triangle);
    ChainWalkExit exit = chain_walk_exit(tri.p0, tri.p1, tri.p2, p.position, delta);
    if (exit.edge < 0) {
      p.position += delta;
      return true;
    }
    int next = neighbours[p.triangle][exit.edge];
    if (next < 0) return false;
    vec3 a = exit.edge == 0 ? tri.p0 : (exit.edge == 1 ? tri.p1 : tri.p2);
    vec3 b = exit.edge == 0 ? tri.p1 : (exit.edge == 1 ? tri.p2 : tri.p0);
    p.position += exit.t * delta;
    delta = chain_unfold((1.0f - exit.t) * delta, a, b, tri.plane_normal, chain_triangle(next).plane_normal);
    p.triangle = next;
  }
  return false;
}

// The first point of `object` along a ray (from inside when `inside`, else from outside); false for anything else.
bool first_point(int object, vec3 origin, vec3 direction, float t_min, bool inside, out SurfacePoint p) {
  p.triangle = -1;
  p.position = origin;
  Hit hit = trace(origin, direction, 1e30f, t_min);
  if (hit.object != object || (dot(hit.geometric_normal, direction) > 0.0f) != inside) return false;
  p.triangle = hit.triangle;
  p.position = vertex_on_ray(chain_triangle(hit.triangle), origin, direction).position;
  return true;
}

// ---- chains from x: the factor and the check ------------------------------------------------------------------
struct Chain {
  bool valid;
  ChainExit exit;
  ChainConstraint constraint;
  vec3 points[3];  // x, the reflection, the exit point
  int point_count;
  float exit_offset;
};

Chain trace_chain(int object, vec3 x, vec3 w, int reflections, LightTarget light) {
  Chain chain;
  chain.valid = false;
  chain.points[0] = x;
  chain.point_count = 1;
  chain.exit_offset = 0.0f;
  float eta = eta_of(object);
  ChainState state = chain_start(x, w);
  float t_min = 0.0f;
  // loop bound: checked; at most 2 (kChainMaxReflections + 1) (each iteration counted in loop_count, budgeted by random_walk.cpp)
  for (int j = 0; j <= reflections && j < 2; ++j) {
    ++loop_count;
    Hit hit = trace(state.y, state.d, 1e30f, t_min);
    if (hit.object != object || dot(hit.geometric_normal, state.d) <= 0.0f) return chain;
    ChainVertex v = vertex_on_ray(chain_triangle(hit.triangle), state.y, state.d);
    state = chain_advance(state, v);
    chain.points[chain.point_count++] = state.y;
    if (j < reflections) {
      state = chain_reflect(state, v, eta);
      t_min = hit.offset;
      continue;
    }
    chain.exit = chain_refract_out(state, v, eta);
    chain.exit_offset = hit.offset;
    chain.constraint = light.point ? chain_constraint_point(chain.exit, light.position)
                                   : chain_constraint_directional(chain.exit, light.direction);
    chain.valid = chain.constraint.refracts;
  }
  return chain;
}

struct Root {
  bool found;
  vec3 w;
  Chain chain;
};

Root polish(int object, vec3 x, vec3 w, int reflections, LightTarget light) {
  Root root;
  root.found = false;
  root.w = w;
  ChainNewton newton = chain_newton_start();
  vec3 good = w;
  vec2 step = vec2(0.0f);
  // loop bound: checked; kChainMaxPolish (3) (each iteration counted in loop_count, budgeted by random_walk.cpp)
  for (int i = 0; i < kChainMaxPolish; ++i) {
    ++loop_count;
    Chain chain = trace_chain(object, x, w, reflections, light);
    // In float the way out cannot be resolved below what the rounding of the exit point's coordinates turns it by.
    float tolerance = kChainDirectionTolerance;
    if (chain.valid) {
      float turns = (length(chain.exit.do_u) + length(chain.exit.do_v)) /
                    max(length(chain.exit.de_u) + length(chain.exit.de_v), 1e-30f);
      tolerance = max(tolerance, kChainRounding * offset_at(chain.exit.e) * turns);
    }
    newton = chain_newton_judge(newton, chain.valid, length(chain.constraint.residual), tolerance);
    if (newton.converged) {
      root.found = true;
      root.w = w;
      root.chain = chain;
      return root;
    }
    if (newton.failed) break;
    if (newton.accepted) {
      ChainStep2 fresh = chain_newton_step2(chain.constraint.residual, chain.constraint.j_u, chain.constraint.j_v, 0.1f);
      if (!fresh.ok) break;
      good = w, step = fresh.step;
    }
    w = chain_direction_step(good, newton.fraction * step);
  }
  return root;
}

// ---- chains from boundary points: the solvers -------------------------------------------------------------------
ChainState light_at(LightTarget light, vec3 e, ChainBasis basis) {
  vec3 travel = light_travel_at(light, e);
  vec3 dtravel_u = vec3(0.0f), dtravel_v = vec3(0.0f);
  if (light.point) {
    float r = length(e - light.position);
    dtravel_u = (basis.u - travel * dot(travel, basis.u)) / r;
    dtravel_v = (basis.v - travel * dot(travel, basis.v)) / r;
  }
  return chain_start_at(e, travel, basis.u, basis.v, dtravel_u, dtravel_v);
}

struct SurfaceEvaluation {
  bool valid;
  vec2 r_a, r_b;
  vec2 a_e_u, a_e_v, a_r_u, a_r_v, b_e_u, b_e_v, b_r_u, b_r_v;
  float relative;
  vec3 first_vertex;
  vec3 arrival;     // the way the light travels when it reaches x
  int orientation;  // unreflected: the sign of the Jacobian's determinant (0: not taken)
  ChainBasis basis_e, basis_r;
};

SurfaceEvaluation surface_evaluation(int object, SurfacePoint e, SurfacePoint r, int reflections, LightTarget light,
                                     vec3 x) {
  SurfaceEvaluation v;
  v.valid = false;
  v.r_a = v.r_b = v.a_e_u = v.a_e_v = v.a_r_u = v.a_r_v = v.b_e_u = v.b_e_v = v.b_r_u = v.b_r_v = vec2(0.0f);
  v.relative = 0.0f;
  v.first_vertex = e.position;
  v.arrival = vec3(0.0f, 0.0f, 1.0f);
  v.orientation = 0;
  float eta = eta_of(object);
  ChainTriangle tri_e = chain_triangle(e.triangle);
  v.basis_e = chain_plane_basis(tri_e.p0, tri_e.p1, tri_e.p2);
  v.basis_r = v.basis_e;
  ChainEntry entry = chain_refract_in(light_at(light, e.position, v.basis_e), vertex_at(tri_e, e.position), eta);
  if (!entry.refracts) return v;
  if (reflections == 0) {
    ChainMiss miss = chain_miss(entry.state, x);
    v.valid = miss.along > 0.0f;
    v.r_a = miss.residual, v.a_e_u = miss.j_u, v.a_e_v = miss.j_v;
    v.relative = length(miss.residual) / max(miss.distance, 1e-30f);
    v.arrival = entry.state.d;
    float det = miss.j_u.x * miss.j_v.y - miss.j_v.x * miss.j_u.y;
    v.orientation = det > 0.0f ? 1 : (det < 0.0f ? -1 : 0);
    return v;
  }
  ChainTriangle tri_r = chain_triangle(r.triangle);
  v.basis_r = chain_plane_basis(tri_r.p0, tri_r.p1, tri_r.p2);
  // r on the refracted ray from e (its miss by e's coordinates, and by r's), x on the ray reflected at r.
  ChainMiss a_e = chain_miss(entry.state, r.position);
  vec3 zero = vec3(0.0f);
  ChainMiss a_r = chain_miss(chain_start_at(e.position, entry.state.d, -v.basis_r.u, -v.basis_r.v, zero, zero), r.position);
  vec3 to_r = r.position - e.position;
  float len = length(to_r);
  vec3 d = to_r / len;
  ChainVertex vertex_r = vertex_at(tri_r, r.position);
  if (!(dot(d, vertex_r.shading_normal) > 0.0f)) return v;
  vec3 de_u = -(v.basis_e.u - d * dot(d, v.basis_e.u)) / len, de_v = -(v.basis_e.v - d * dot(d, v.basis_e.v)) / len;
  vec3 dr_u = (v.basis_r.u - d * dot(d, v.basis_r.u)) / len, dr_v = (v.basis_r.v - d * dot(d, v.basis_r.v)) / len;
  ChainState by_e = chain_reflect(chain_start_at(r.position, d, zero, zero, de_u, de_v), vertex_r, eta);
  ChainState by_r = chain_reflect(chain_start_at(r.position, d, v.basis_r.u, v.basis_r.v, dr_u, dr_v), vertex_r, eta);
  ChainMiss b_e = chain_miss(by_e, x), b_r = chain_miss(by_r, x);
  v.valid = a_e.along > 0.0f && b_e.along > 0.0f;
  v.r_a = a_e.residual, v.r_b = b_e.residual;
  v.a_e_u = a_e.j_u, v.a_e_v = a_e.j_v, v.a_r_u = a_r.j_u, v.a_r_v = a_r.j_v;
  v.b_e_u = b_e.j_u, v.b_e_v = b_e.j_v, v.b_r_u = b_r.j_u, v.b_r_v = b_r.j_v;
  v.relative = length(a_e.residual) / max(a_e.distance, 1e-30f) + length(b_e.residual) / max(b_e.distance, 1e-30f);
  v.first_vertex = r.position;
  v.arrival = by_e.d;
  return v;
}

struct SurfaceRoot {
  bool found;
  int reflections;
  vec3 vertex;  // the chain's first vertex seen from x
  float size;         // of its triangle
  float uncertainty;  // how far the vertex may lie from the exact solution: the Newton step left there
  SurfacePoint point;  // the exit point e
  vec3 w;              // the way the chain leaves x: against the light's last leg (exact however far x is)
  int orientation;     // unreflected: the sign of the Jacobian's determinant (0: not taken)
};

SurfaceRoot no_root() {
  SurfaceRoot z;
  z.found = false;
  z.reflections = 0;
  z.vertex = vec3(0.0f);
  z.size = 0.0f;
  z.uncertainty = 0.0f;
  z.w = vec3(0.0f, 0.0f, 1.0f);
  z.orientation = 0;
  z.point.triangle = -1;
  z.point.position = vec3(0.0f);
  return z;
}

// As volpath's: within a fraction of a triangle, float rounding, or what the solves leave uncertain, and turning the
// same way (the two chains at a caustic's fold have Jacobians of opposite sign).
bool same_chain(SurfaceRoot a, SurfaceRoot b) {
  float tolerance = max(max(kChainSame * max(a.size, b.size), 8.0f * offset_at(a.vertex)),
                        4.0f * (a.uncertainty + b.uncertainty));
  return a.found && b.found && a.reflections == b.reflections &&
         (a.orientation == 0 || b.orientation == 0 || a.orientation == b.orientation) &&
         length(a.vertex - b.vertex) < tolerance;
}

// How close to a solution's first vertex its chain polished from x must lie to confirm it (volpath's kConfirmed).
float confirmed_distance(SurfaceRoot z) {
  return max(max(kChainConfirmed * z.size, 8.0f * offset_at(z.vertex)), 4.0f * z.uncertainty);
}

// ---- the estimate: one call of each solver, ray and evaluation (the shader compiler inlines every call) ---------

// One solve on the boundary from seed points (e; with a reflection also r), walking across the mesh or projecting
// long steps from x (the only ray traced inside it).
SurfaceRoot solve(int object, vec3 x, SurfacePoint e, SurfacePoint r, int reflections, LightTarget light) {
  WalkObjectGPU o = walk_objects[object];
  float max_step = kChainMaxStepOfRadius * 0.5f * length(o.mesh_upper.xyz - o.mesh_lower.xyz);
  ChainNewton newton = chain_newton_start();
  SurfacePoint good_e = e, good_r = r;
  ChainBasis basis_e = chain_basis(vec3(0.0f, 0.0f, 1.0f)), basis_r = basis_e;
  vec2 step_e = vec2(0.0f), step_r = vec2(0.0f);
  // Evaluations alternate with moves; a move is a walk, or a projection by one ray (of the reflection first, then of
  // the exit point): `pending` counts the points still to place before the next evaluation.
  int pending = 0, placing = 0;
  // loop bound: checked; kChainMaxEvaluations evaluations (16) and their moves (at most 6 shortened tries of 2 points
  // each), every iteration counted in loop_count (budgeted by random_walk.cpp)
  for (int i = 0; i < kChainMaxEvaluations * 14; ++i) {
    ++loop_count;
    if (pending == 0) {
      SurfaceEvaluation v = surface_evaluation(object, e, r, reflections, light, x);
      // In float the miss cannot fall below the rounding of the points' coordinates: near x that is the larger part.
      float tolerance = max(kChainSurfaceTolerance,
                            kChainRounding * offset_at(v.first_vertex) / max(length(v.first_vertex - x), 1e-30f));
      newton = chain_newton_judge(newton, v.valid, v.relative, tolerance);
      if (newton.converged) {
        SurfaceRoot z;
        z.found = true;
        z.reflections = reflections;
        z.vertex = v.first_vertex;
        z.size = chain_triangle(reflections == 0 ? e.triangle : r.triangle).size;
        z.uncertainty = 0.0f;
        if (reflections == 0) {
          ChainStep2 left = chain_newton_step2(v.r_a, v.a_e_u, v.a_e_v, 1e30f);
          if (left.ok) z.uncertainty = length(left.step);
        } else {
          ChainStep4 left = chain_newton_step4(v.r_a, v.r_b, v.a_e_u, v.a_e_v, v.a_r_u, v.a_r_v, v.b_e_u, v.b_e_v,
                                               v.b_r_u, v.b_r_v, 1e30f);
          if (left.ok) z.uncertainty = length(left.step_q);
        }
        z.point = e;
        z.w = -normalize(v.arrival);
        z.orientation = v.orientation;
        return z;
      }
      if (newton.failed || newton.evaluations >= kChainMaxEvaluations) break;
      if (newton.accepted) {
        good_e = e, good_r = r, basis_e = v.basis_e, basis_r = v.basis_r;
        ChainStep4 fresh;
        if (reflections == 0) {
          ChainStep2 two = chain_newton_step2(v.r_a, v.a_e_u, v.a_e_v, max_step);
          fresh.ok = two.ok, fresh.step_p = two.step, fresh.step_q = vec2(0.0f);
        } else {
          fresh = chain_newton_step4(v.r_a, v.r_b, v.a_e_u, v.a_e_v, v.a_r_u, v.a_r_v, v.b_e_u, v.b_e_v, v.b_r_u,
                                     v.b_r_v, max_step);
        }
        if (!fresh.ok) break;
        step_e = fresh.step_p, step_r = fresh.step_q;
      }
      e = good_e, r = good_r;
      pending = reflections > 0 ? 2 : 1;
      placing = 0;
    }
    // Place the next point: r (with a reflection) from x, then e from x or from r.
    bool reflection = pending == 2;
    vec2 d2 = newton.fraction * (reflection ? step_r : step_e);
    vec3 delta = reflection ? d2.x * basis_r.u + d2.y * basis_r.v : d2.x * basis_e.u + d2.y * basis_e.v;
    SurfacePoint p = reflection ? good_r : good_e;
    vec3 target = p.position + delta;  // before walk(), which moves p part of the way when it fails
    bool moved = length(delta) <= kChainLongStep * chain_triangle(p.triangle).size && walk(p, delta);
    if (!moved) {
      vec3 from = reflection || reflections == 0 ? x : r.position;
      p = reflection ? good_r : good_e;
      moved = first_point(object, from, normalize(target - from), offset_at(from), true, p);
    }
    if (reflection) r = p;
    else e = p;
    --pending;
    if (!moved) {  // a step that leaves the object is shortened
      newton = chain_newton_backtrack(newton);
      if (newton.failed || ++placing > 5) break;
      e = good_e, r = good_r;
      pending = reflections > 0 ? 2 : 1;
    }
  }
  return no_root();
}

// Where the straight line from x along `direction` leaves the object; where the light refracted in at e meets the
// boundary again; the rim seed (volpath's rim_seed): from the primary chain's exit point along its circle of
// curvature in the plane of its normal and the light, to where the light meets the boundary at cos_i =
// kChainRimCosine, for x beyond that circle's centre only. Each as the ray that finds it (origin, direction, the
// side it meets), for the one ray call.
struct SeedRay {
  bool valid;
  vec3 origin, direction;
  float t_min;
  bool inside;
};

SeedRay seed_ray_along(vec3 x, vec3 direction) {
  SeedRay ray;
  ray.valid = true, ray.origin = x, ray.direction = direction, ray.t_min = 0.0f, ray.inside = true;
  return ray;
}

SeedRay seed_ray_refracted(int object, SurfacePoint e, LightTarget light) {
  SeedRay ray;
  ray.valid = false, ray.origin = e.position, ray.direction = vec3(0.0f, 0.0f, 1.0f), ray.t_min = 0.0f, ray.inside = true;
  ChainTriangle tri = chain_triangle(e.triangle);
  ChainEntry entry = chain_refract_in(light_at(light, e.position, chain_plane_basis(tri.p0, tri.p1, tri.p2)),
                                      vertex_at(tri, e.position), eta_of(object));
  if (!entry.refracts) return ray;
  ray.valid = true, ray.direction = normalize(entry.state.d), ray.t_min = offset_at(e.position);
  return ray;
}

SeedRay seed_ray_rim(int object, vec3 x, SurfacePoint primary, LightTarget light) {
  SeedRay ray;
  ray.valid = false, ray.origin = x, ray.direction = vec3(0.0f, 0.0f, 1.0f), ray.t_min = 0.0f, ray.inside = false;
  ChainVertex v = vertex_at(chain_triangle(primary.triangle), primary.position);
  vec3 travel = light_travel_at(light, primary.position), n = v.shading_normal;
  vec3 side = n - dot(n, travel) * travel, tangent = travel - dot(travel, n) * n;
  if (!(length(side) > 1e-6f) || !(length(tangent) > 1e-6f)) return ray;
  float curvature = length(chain_normal_change(v, normalize(tangent)));
  if (!(curvature > 0.0f)) return ray;
  vec3 centre = primary.position - n / curvature;
  if (!(dot(x - centre, travel) > 0.0f)) return ray;
  vec3 n_rim = -kChainRimCosine * travel + sqrt(1.0f - kChainRimCosine * kChainRimCosine) * normalize(side);
  vec3 target = centre + n_rim / curvature;
  WalkObjectGPU o = walk_objects[object];
  vec3 origin = light.point ? light.position : target - 2.0f * length(o.mesh_upper.xyz - o.mesh_lower.xyz) * travel;
  ray.valid = true, ray.origin = origin, ray.direction = normalize(target - origin), ray.t_min = offset_at(origin);
  return ray;
}

// A point uniform over the object's surface (its triangles' area distribution; mesh_lower.w / mesh_upper.w: the
// first and count of its entries), and one that faces the light (the first of a few).
SurfacePoint random_point(int object) {
  WalkObjectGPU o = walk_objects[object];
  int first = floatBitsToInt(o.mesh_lower.w), count = floatBitsToInt(o.mesh_upper.w);
  float u = rnd();
  int lo = 0, hi = count - 1;
  // loop bound: checked; 32 halvings of a range of at most 2^31 entries (each iteration counted in loop_count, budgeted by random_walk.cpp)
  for (int i = 0; i < 32 && lo < hi; ++i) {
    ++loop_count;
    int mid = (lo + hi) / 2;
    if (surface_cdf[first + mid].x < u) lo = mid + 1;
    else hi = mid;
  }
  SurfacePoint p;
  p.triangle = floatBitsToInt(surface_cdf[first + lo].y);
  ChainTriangle tri = chain_triangle(p.triangle);
  float s = sqrt(rnd()), b1 = rnd() * s, b0 = 1.0f - s;
  p.position = b0 * tri.p0 + b1 * tri.p1 + (1.0f - b0 - b1) * tri.p2;
  return p;
}

bool random_facing_point(int object, LightTarget light, out SurfacePoint e) {
  // loop bound: checked; kChainFacingTries (8) (each iteration counted in loop_count, budgeted by random_walk.cpp)
  for (int i = 0; i < kChainFacingTries; ++i) {
    ++loop_count;
    e = random_point(object);
    if (dot(vertex_at(chain_triangle(e.triangle), e.position).shading_normal, light_travel_at(light, e.position)) < 0.0f)
      return true;
  }
  return false;
}

// The light a chain found from x along w brings to x (polished there first), scattered toward -path_dir: 0 when the
// polished chain's first vertex is not within `confirm` of the solution's (volpath's root_light).
vec3 root_light(int object, vec3 x, vec3 path_dir, vec3 w, int reflections, vec3 vertex, float confirm,
                LightTarget light, vec3 light_radiance, LightGPU gpu_light) {
  Root root = polish(object, x, w, reflections, light);
  if (!root.found) return vec3(0.0f);
  Chain chain = root.chain;
  if (length(chain.points[1] - vertex) > confirm) return vec3(0.0f);
  float factor = chain_radiance_factor(chain.exit, chain.constraint, eta_of(object));
  if (!(factor > 0.0f) || isinf(factor)) return vec3(0.0f);
  vec3 e = chain.exit.e;
  vec3 travel = light_travel_at(light, e);
  vec3 e_outside = e - 2.0f * chain.exit_offset * travel;
  vec3 radiance = light_radiance;
  float t_max = 1e30f;
  if (light.point) {
    float r = length(light.position - e);
    radiance = point_intensity(gpu_light, travel) / (r * r);
    t_max = length(light.position - e_outside) - offset_at(light.position);
  }
  vec3 outside = shadow_transmittance(e_outside, -travel, t_max);
  if (max3(outside) <= 0.0f) return vec3(0.0f);
  vec3 inside = vec3(1.0f);
  if (heterogeneous(object)) {
    // loop bound: checked; at most 2 segments (one reflection) (each iteration counted in loop_count, budgeted by random_walk.cpp)
    for (int i = 0; i + 1 < chain.point_count && i < 2; ++i) {
      ++loop_count;
      inside *= transmittance(object, chain.points[i], chain.points[i + 1]);
    }
  } else {
    inside = exp(-sigma_t_of(object) * chain.exit.path_length);
  }
  return radiance * factor * outside * inside * hg_phase_between(root.w, path_dir, walk_objects[object].g.xyz);
}

// The estimate's solutions, each with its weight: the known chains (found from deterministic seeds, each counted
// once), and a chain found by specular manifold sampling times its count of trials over its probability.
const int kChainMaxKnown = 8;  // known chains (found from deterministic seeds) of one number of reflections
const int kChainMaxSolutions = 2 * kChainMaxKnown + 2;  // the known ones and one sampled, of 0 and 1 reflections

// The light's direction inside after refraction through a face of normal n (at the side the light meets).
vec3 refracted_inside(vec3 travel, vec3 n, float eta) {
  float cos_i = -dot(travel, n);
  float cos_t = sqrt(max(0.0f, 1.0f - (1.0f - cos_i * cos_i) / (eta * eta)));
  return normalize(travel / eta + (cos_i / eta - cos_t) * n);
}

// In-scattered radiance at medium vertex x of `object` toward -path_dir from light l (outside the medium), as volpath's
// light_through_chains: the solves run in phases, one seed ray and one solve per step (the shader compiler inlines
// every call, so each has one call site):
//  0  the unreflected chain from where the straight line toward the light leaves,
//  1  from the rim seed,
//  2  from each large flat face's seed facing the light (the light refracted by the face, traced back from x),
//  3  with probability kChainOtherProbability, a manifold-sampling trial for the other unreflected chains, then its
//     recounting trials,
//  4  where the first solution's light would leave past x, and with the probability `reflected` that follows the
//     transmittance to there and back, the chains reflected once inside:
//  5  from each unreflected solution's exit point with where its light would leave past x, and with each other flat
//     face where its light reflected there, traced back from x, meets it,
//  6  manifold sampling, as in 3.
// At eta = 1 the light goes straight: one chain, along the line toward it.
vec3 light_through_boundary(int object, vec3 x, vec3 path_dir, int l) {
  LightGPU gpu_light = frame.lights[l];
  LightTarget light;
  light.point = int(gpu_light.position.w) != LUCENT_LIGHT_DIRECTIONAL;
  light.direction = light.point ? vec3(0.0f, 0.0f, 1.0f) : normalize(gpu_light.position.xyz);
  light.position = gpu_light.position.xyz;
  vec3 radiance = light.point ? vec3(0.0f) : gpu_light.power.rgb;

  vec3 solution_w[kChainMaxSolutions], solution_vertex[kChainMaxSolutions];
  int solution_reflections[kChainMaxSolutions];
  float solution_weight[kChainMaxSolutions], solution_confirm[kChainMaxSolutions];
  int solutions = 0;
  if (eta_of(object) == 1.0f) {
    solution_w[0] = light_toward_from(light, x), solution_reflections[0] = 0, solution_weight[0] = 1.0f;
    solution_vertex[0] = x, solution_confirm[0] = 1e30f;
    solutions = 1;
  } else {
    ivec4 faces = walk_objects[object].faces;
    faces.y = min(faces.y, 16);  // walk_boundary.cpp uploads 16 at most; the loop's bound counts on it
    float eta = eta_of(object);
    SurfaceRoot unreflected[kChainMaxKnown], once[kChainMaxKnown], sampled = no_root();
    int unreflected_count = 0, once_count = 0;
    // The entries of reflected chains: each unreflected solution's exit point with the way its light goes inside,
    // or, where none was found, the straight line's exit with the light's way.
    SurfacePoint toward = no_root().point;
    bool has_toward = false;
    float reflected = 1.0f;
    int phase = 0, index = 0, face = -1, trials = 0;
    // A recount ends after kChainRecountLoops loop iterations (llvmpipe's loop cap would end the path otherwise).
    uint recount_end = 0u;
    // loop bound: checked; the deterministic seeds (2 + faces, then kChainMaxKnown x (1 + faces), faces at most 16)
    // and two manifold samplings of at most 1 + kChainMaxTrials solves each, every iteration counted in loop_count
    // (budgeted by random_walk.cpp)
    for (int i = 0; phase < 7 && i < 2 + 16 + kChainMaxKnown * 17 + 2 * (kChainMaxTrials + 1) + 8; ++i) {
      ++loop_count;
      int m = phase < 4 ? 0 : 1;
      // The seed of this step and the ray that finds it.
      SeedRay ray;
      ray.valid = false;
      bool have_seed = false, solving = true;
      SurfacePoint e = no_root().point, r = e;
      if (phase == 0) ray = seed_ray_along(x, light_toward_from(light, x));
      if (phase == 1 && unreflected_count > 0) ray = seed_ray_rim(object, x, unreflected[0].point, light);
      if (phase == 2 && index < faces.y) {
        vec3 n = flat_faces[faces.x + index].xyz, travel = light_travel_at(light, x);
        if (dot(n, travel) < 0.0f) ray = seed_ray_along(x, -refracted_inside(travel, n, eta));
      }
      if (phase == 3 || phase == 6) {
        if (random_facing_point(object, light, e)) {
          if (m == 0) have_seed = true;
          else ray = seed_ray_refracted(object, e, light);
        }
      }
      SurfacePoint entry =
          unreflected_count > 0 ? unreflected[clamp(index, 0, min(unreflected_count, kChainMaxKnown) - 1)].point : toward;
      vec3 w = unreflected_count > 0 ? normalize(x - entry.position) : -light_toward_from(light, x);  // the light's way
      if (phase == 4) ray = seed_ray_along(x, w), solving = false;
      if (phase == 5) {
        e = entry;
        if (face < 0) {
          ray = seed_ray_along(x, w);
        } else {
          vec3 n = flat_faces[faces.x + face].xyz;
          int entry_face = neighbours[entry.triangle].w;
          if (entry_face >= 0 && faces.x + face != entry_face && dot(w, n) > 0.0f)
            ray = seed_ray_along(x, -(w - 2.0f * dot(w, n) * n));
        }
      }
      SurfacePoint found = e;
      bool hit = ray.valid && first_point(object, ray.origin, ray.direction, ray.t_min, ray.inside, found);
      if (ray.valid) {
        have_seed = hit;
        if (phase == 0) toward = found, has_toward = hit;
        if (phase == 2) have_seed = hit && neighbours[found.triangle].w == faces.x + index;
        if (phase == 5 && face >= 0) have_seed = hit && neighbours[found.triangle].w == faces.x + face;
        if (m == 0) e = found;
        else r = found;
      }
      SurfaceRoot z = have_seed && solving ? solve(object, x, e, r, m, light) : no_root();
      bool known = false;
      // loop bound: checked; kChainMaxKnown (8) (counted in loop_count, budgeted by random_walk.cpp)
      for (int k = 0; k < kChainMaxKnown; ++k) {
        ++loop_count;
        if (k < (m == 0 ? unreflected_count : once_count) && same_chain(m == 0 ? unreflected[k] : once[k], z)) known = true;
      }
      // What the step means, and the next one.
      if (phase == 0 || phase == 1 || phase == 2 || phase == 5) {
        if (z.found && !known) {
          if (m == 0 && unreflected_count < kChainMaxKnown) unreflected[unreflected_count++] = z;
          if (m == 1 && once_count < kChainMaxKnown) once[once_count++] = z;
        }
        if (phase == 0 || phase == 1) {
          ++phase, index = 0;
        } else if (phase == 2) {
          if (++index >= faces.y) phase = 3, index = 0, trials = 0;
        } else if (++face >= faces.y || neighbours[entry.triangle].w < 0) {
          face = -1;
          if (++index >= max(1, unreflected_count)) phase = 6, trials = 0;
        }
        if (phase == 3 || phase == 6) {  // the known chains are solutions of weight 1 (1 / reflected)
          // loop bound: checked; kChainMaxKnown (8) (counted in loop_count, budgeted by random_walk.cpp)
          for (int k = 0; k < kChainMaxKnown; ++k) {
            ++loop_count;
            if (k >= (m == 0 ? unreflected_count : once_count) || solutions >= kChainMaxSolutions) break;
            SurfaceRoot known_root = m == 0 ? unreflected[k] : once[k];
            solution_w[solutions] = known_root.w, solution_vertex[solutions] = known_root.vertex;
            solution_confirm[solutions] = confirmed_distance(known_root);
            solution_reflections[solutions] = m;
            solution_weight[solutions++] = m == 0 ? 1.0f : 1.0f / reflected;
          }
          if (!(rnd() < kChainOtherProbability)) phase = m == 0 ? (has_toward ? 4 : 7) : 7;
        }
      } else if (phase == 4) {
        vec3 sigma_t = sigma_t_of(object);
        float back_and_forth = hit ? 2.0f * min(sigma_t.x, min(sigma_t.y, sigma_t.z)) * length(found.position - x) : 0.0f;
        reflected = clamp(exp(-back_and_forth), kChainLeastReflectedProbability, 1.0f);
        phase = rnd() < reflected ? 5 : 7, index = 0, face = -1;
      } else if (trials == 0) {  // phases 3 and 6: the first trial
        if (z.found && !known) {
          sampled = z, trials = 1;
          recount_end = loop_count + kChainRecountLoops;
        } else {
          phase = phase == 3 && has_toward ? 4 : 7;
        }
      } else if (!same_chain(z, sampled) && trials < kChainMaxTrials && loop_count < recount_end) {
        ++trials;  // recounting until found again
      } else {
        if (solutions < kChainMaxSolutions) {
          solution_w[solutions] = sampled.w, solution_reflections[solutions] = m;
          solution_vertex[solutions] = sampled.vertex, solution_confirm[solutions] = confirmed_distance(sampled);
          solution_weight[solutions++] = float(trials) / (kChainOtherProbability * (m == 0 ? 1.0f : reflected));
        }
        phase = phase == 3 && has_toward ? 4 : 7;
      }
    }
  }
  vec3 L = vec3(0.0f);
  // loop bound: checked; kChainMaxSolutions (16) (each iteration counted in loop_count, budgeted by random_walk.cpp)
  for (int k = 0; k < solutions && k < kChainMaxSolutions; ++k) {
    ++loop_count;
    L += solution_weight[k] * root_light(object, x, path_dir, solution_w[k], solution_reflections[k], solution_vertex[k],
                                         solution_confirm[k], light, radiance, gpu_light);
  }
  return L;
}
