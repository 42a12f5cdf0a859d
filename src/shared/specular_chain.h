// specular_chain.h: light from a delta light to a medium vertex through a curved dielectric boundary, C++ (double)
// and GLSL (float). The light reaches vertex x along a specular chain: it refracts into the medium at an exit
// vertex e (seen from x) after m internal reflections at the vertices before it. The chain is parametrized by the
// direction w in which it leaves x (manifold next-event estimation, Hanika, Droske and Fascione 2015, in the
// direction parametrization): trace from x along w, reflect m times, refract out at e with the interpolated normal;
// the chain carries light when the outgoing direction o(w) points at the light. Newton's method solves o(w) = the
// light's direction, with the exact derivative do/dw propagated through every vertex (forward differentiation of
// ray-plane intersection, interpolated normal, reflection and refraction), and the same derivative is the
// generalized geometry term: the radiance the light delivers along the chain is, per unit of the light's radiance
// integrated over directions (irradiance E of a directional light, I / r^2 of a point light),
//
//   eta^2 T(e) prod F(r_j) / |det(d o / d w)|        (directional)
//   eta^2 T(e) prod F(r_j) / |det(d (o - v) / d w)|  (point light: v = the direction from e to the light)
//
// with T the Fresnel transmittance at the exit vertex, F the internal reflectances, det taken between the
// tangent planes of w and o. It is the delta of the light's direction pulled back through the chain to the
// directions of x, i.e. the convention in which a camera path samples the same boundary (refraction about the
// interpolated normal, radiance scaled by eta^2 across it). On a flat boundary it reduces to T cos_i / cos_t (and for a
// point light to the flux through its refracted pencil; tested against a ray bundle); behind a curved one it holds the
// focusing that the flat factor misses. The derivation and its checks: docs/references.md, "volpath: delta lights
// behind refracting boundaries".
//
// Vertices come from triangles with per-vertex normals: the normal field n(y) = normalize(sum b_i n_i) is smooth
// on each triangle, so d n / d y is exact there (chain_vertex_on_triangle).
#ifndef LUCENT_SHARED_SPECULAR_CHAIN_H
#define LUCENT_SHARED_SPECULAR_CHAIN_H
#include "bssrdf/fresnel.h"
#include "shared/bridge.h"

// The chain's precision: double on the CPU, float in shaders.
#if defined(__cplusplus)
LUCENT_SHADER_BEGIN
using creal = double;
using creal2 = glm::dvec2;
using creal3 = glm::dvec3;
LUCENT_SHADER_END
#define LUCENT_CREAL(x) double(x)
#else
#define creal float
#define creal2 vec2
#define creal3 vec3
#define LUCENT_CREAL(x) float(x)
#endif

LUCENT_SHADER_BEGIN

// A point where the chain meets the boundary.
struct ChainVertex {
  creal3 position;           // on the triangle's plane [scene units]
  creal3 geometric_normal;   // the plane's unit normal (either side)
  creal3 shading_normal;     // interpolated, unit, out of the object
  // The interpolated normal's derivative (chain_normal_change): n = m / |m| with m = n0 + b1 (n1 - n0) + b2 (n2 - n0),
  // b_k = (y - p0) . g_k.
  creal3 dm1, dm2;  // n1 - n0, n2 - n0
  creal3 g1, g2;    // the dual basis of the triangle's edges
  creal inverse_length_m;
  creal t;                   // distance from the ray's origin
};

// The vertex at point y of the plane of triangle (p0, p1, p2) with corner normals (n0, n1, n2) (its barycentrics
// may lie slightly outside [0, 1] near an edge).
LUCENT_INLINE ChainVertex chain_vertex_at(creal3 y, creal3 p0, creal3 p1, creal3 p2, creal3 n0, creal3 n1, creal3 n2) {
  ChainVertex v;
  creal3 e1 = p1 - p0, e2 = p2 - p0, N = cross(e1, e2);
  creal area2 = dot(N, N);
  v.geometric_normal = N / sqrt(area2);
  v.position = y;
  v.t = LUCENT_CREAL(0.0);
  // Barycentrics through the dual basis of (e1, e2) in the plane: b1 = (y - p0) . g1, b2 = (y - p0) . g2.
  creal3 g1 = cross(e2, N) / area2, g2 = cross(N, e1) / area2;
  creal3 q = y - p0;
  creal b1 = dot(q, g1), b2 = dot(q, g2);
  v.dm1 = n1 - n0;
  v.dm2 = n2 - n0;
  v.g1 = g1;
  v.g2 = g2;
  creal3 m = n0 + b1 * v.dm1 + b2 * v.dm2;
  v.inverse_length_m = LUCENT_CREAL(1.0) / length(m);
  v.shading_normal = m * v.inverse_length_m;
  return v;
}

// The change of the vertex's shading normal for a displacement dy in the triangle's plane:
// d n = (I - n n^T) d m / |m|, d m = (n1 - n0) (g1 . dy) + (n2 - n0) (g2 . dy).
LUCENT_INLINE creal3 chain_normal_change(ChainVertex v, creal3 dy) {
  creal3 dm = v.dm1 * dot(v.g1, dy) + v.dm2 * dot(v.g2, dy);
  return (dm - v.shading_normal * dot(v.shading_normal, dm)) * v.inverse_length_m;
}

// The vertex where the ray (origin, direction) meets the plane of the triangle.
LUCENT_INLINE ChainVertex chain_vertex_on_triangle(creal3 origin, creal3 direction, creal3 p0, creal3 p1, creal3 p2,
                                                   creal3 n0, creal3 n1, creal3 n2) {
  creal3 N = cross(p1 - p0, p2 - p0);
  creal t = dot(p0 - origin, N) / dot(direction, N);
  ChainVertex v = chain_vertex_at(origin + t * direction, p0, p1, p2, n0, n1, n2);
  v.t = t;
  return v;
}

// An orthonormal basis of the plane perpendicular to unit w (Duff et al. 2017), the coordinates of the chain's
// unknown: the direction w + a u + b v, normalized.
struct ChainBasis {
  creal3 u, v;
};
LUCENT_INLINE ChainBasis chain_basis(creal3 w) {
  creal s = w.z >= LUCENT_CREAL(0.0) ? LUCENT_CREAL(1.0) : LUCENT_CREAL(-1.0);
  creal a = LUCENT_CREAL(-1.0) / (s + w.z), b = w.x * w.y * a;
  ChainBasis basis;
  basis.u = creal3(LUCENT_CREAL(1.0) + s * w.x * w.x * a, s * b, -s * w.x);
  basis.v = creal3(b, s + w.y * w.y * a, -w.y);
  return basis;
}

// The chain so far: its last point y and direction d, their derivatives along the two coordinates of w, the path
// length inside and the product of the internal reflectances.
struct ChainState {
  creal3 y, d;
  creal3 dy_u, dy_v, dd_u, dd_v;
  creal path_length;  // [scene units]
  creal reflectance;
};

LUCENT_INLINE ChainState chain_start(creal3 x, creal3 w) {
  ChainBasis basis = chain_basis(w);
  ChainState s;
  s.y = x;
  s.d = w;
  s.dy_u = creal3(LUCENT_CREAL(0.0));
  s.dy_v = creal3(LUCENT_CREAL(0.0));
  s.dd_u = basis.u;
  s.dd_v = basis.v;
  s.path_length = LUCENT_CREAL(0.0);
  s.reflectance = LUCENT_CREAL(1.0);
  return s;
}

// Along d to the vertex's plane: y' = y + t d, t = (p - y) . N / (d . N), and its derivative.
LUCENT_INLINE ChainState chain_advance(ChainState s, ChainVertex vertex) {
  creal3 N = vertex.geometric_normal;
  creal t = dot(vertex.position - s.y, N) / dot(s.d, N);
  creal dn = dot(s.d, N);
  creal dt_u = -(dot(s.dy_u, N) + t * dot(s.dd_u, N)) / dn;
  creal dt_v = -(dot(s.dy_v, N) + t * dot(s.dd_v, N)) / dn;
  s.dy_u = s.dy_u + dt_u * s.d + t * s.dd_u;
  s.dy_v = s.dy_v + dt_v * s.d + t * s.dd_v;
  s.y = s.y + t * s.d;
  s.path_length += t;
  return s;
}

// d' = d - 2 (d . n) n and its derivative, at a vertex the state has advanced to; the reflectance of the boundary
// from inside (relative index 1 / eta) multiplies the chain's.
LUCENT_INLINE ChainState chain_reflect(ChainState s, ChainVertex vertex, creal eta) {
  creal3 n = vertex.shading_normal;
  creal3 dn_u = chain_normal_change(vertex, s.dy_u), dn_v = chain_normal_change(vertex, s.dy_v);
  creal c = dot(s.d, n);
  s.reflectance *= creal(fresnel_reflectance(float(LUCENT_CREAL(1.0) / eta), float(abs(c))));
  s.dd_u = s.dd_u - LUCENT_CREAL(2.0) * ((dot(s.dd_u, n) + dot(s.d, dn_u)) * n + c * dn_u);
  s.dd_v = s.dd_v - LUCENT_CREAL(2.0) * ((dot(s.dd_v, n) + dot(s.d, dn_v)) * n + c * dn_v);
  s.d = s.d - LUCENT_CREAL(2.0) * c * n;
  return s;
}

// The chain leaving the medium at its last vertex: the outgoing direction o (toward where the light must be) and
// its derivatives, the exit point's derivatives, and the transmittance of the boundary for light entering there.
struct ChainExit {
  bool refracts;  // false under total internal reflection
  creal3 o, do_u, do_v;
  creal3 e, de_u, de_v;
  creal transmittance;  // T = 1 - F at the exit, for the light coming in
  creal reflectance;    // the internal reflectances before it
  creal path_length;    // the path length inside, x to e [scene units]
};

LUCENT_INLINE ChainExit chain_refract_out(ChainState s, ChainVertex vertex, creal eta) {
  ChainExit exit;
  exit.e = s.y;
  exit.de_u = s.dy_u;
  exit.de_v = s.dy_v;
  exit.reflectance = s.reflectance;
  exit.path_length = s.path_length;
  // The normal on the side the chain arrives from (it leaves the object: d . n > 0).
  creal3 n = -vertex.shading_normal;
  creal3 dn_u = -chain_normal_change(vertex, s.dy_u), dn_v = -chain_normal_change(vertex, s.dy_v);
  creal ratio = eta;  // n_inside / n_outside: o = ratio d + (ratio cos_i - cos_t) n
  creal cos_i = -dot(s.d, n);
  creal sin2_t = ratio * ratio * (LUCENT_CREAL(1.0) - cos_i * cos_i);
  exit.refracts = cos_i > LUCENT_CREAL(0.0) && sin2_t < LUCENT_CREAL(1.0);
  if (!exit.refracts) return exit;
  creal cos_t = sqrt(LUCENT_CREAL(1.0) - sin2_t);
  exit.o = ratio * s.d + (ratio * cos_i - cos_t) * n;
  creal dcos_i_u = -(dot(s.dd_u, n) + dot(s.d, dn_u)), dcos_i_v = -(dot(s.dd_v, n) + dot(s.d, dn_v));
  creal dcos_t_u = ratio * ratio * cos_i * dcos_i_u / cos_t, dcos_t_v = ratio * ratio * cos_i * dcos_i_v / cos_t;
  exit.do_u = ratio * s.dd_u + (ratio * dcos_i_u - dcos_t_u) * n + (ratio * cos_i - cos_t) * dn_u;
  exit.do_v = ratio * s.dd_v + (ratio * dcos_i_v - dcos_t_v) * n + (ratio * cos_i - cos_t) * dn_v;
  exit.transmittance = creal(fresnel_transmittance(float(eta), float(cos_t)));
  return exit;
}

// The constraint "o points at the light": o against the target direction t (toward the light), as the stereographic
// projection of o from -t onto the plane perpendicular to t, r = 2 P_t(o) / (1 + o . t), which is 0 only at o = t
// (a projection without the denominator is 0 at -t too) and grows monotonically with the angle, so Newton's method
// steps toward t from anywhere on the sphere; at the solution d r = P_t(d o - d t). `residual` and its Jacobian with
// respect to w's coordinates; `refracts`: the chain left the medium at all.
struct ChainConstraint {
  bool refracts;
  creal2 residual;
  creal2 j_u, j_v;  // columns: d residual / d u, d residual / d v
};

LUCENT_INLINE creal chain_jacobian_determinant(ChainConstraint c) { return c.j_u.x * c.j_v.y - c.j_v.x * c.j_u.y; }

// t: the target direction; dt_u, dt_v: its derivatives (zero for a directional light). The basis of t's plane is
// held fixed in the derivative: exact at the solution, where the residual's plane components vanish.
LUCENT_INLINE ChainConstraint chain_constraint_toward(ChainExit exit, creal3 t, creal3 dt_u, creal3 dt_v) {
  ChainConstraint c;
  c.refracts = exit.refracts;
  c.residual = creal2(LUCENT_CREAL(0.0));
  c.j_u = creal2(LUCENT_CREAL(0.0));
  c.j_v = creal2(LUCENT_CREAL(0.0));
  if (!exit.refracts) return c;
  ChainBasis b = chain_basis(t);
  creal denominator = LUCENT_CREAL(1.0) + dot(exit.o, t);
  if (!(denominator > LUCENT_CREAL(1e-12))) {  // o = -t: the projection's pole
    c.refracts = false;
    return c;
  }
  creal2 p = creal2(dot(b.u, exit.o), dot(b.v, exit.o));
  c.residual = LUCENT_CREAL(2.0) * p / denominator;
  creal3 du = exit.do_u - dt_u, dv = exit.do_v - dt_v;
  creal ddenominator_u = dot(exit.do_u, t) + dot(exit.o, dt_u), ddenominator_v = dot(exit.do_v, t) + dot(exit.o, dt_v);
  c.j_u = LUCENT_CREAL(2.0) * (creal2(dot(b.u, du), dot(b.v, du)) / denominator -
                               p * ddenominator_u / (denominator * denominator));
  c.j_v = LUCENT_CREAL(2.0) * (creal2(dot(b.u, dv), dot(b.v, dv)) / denominator -
                               p * ddenominator_v / (denominator * denominator));
  return c;
}

// Directional light travelling along `light_direction`: o must equal -light_direction.
LUCENT_INLINE ChainConstraint chain_constraint_directional(ChainExit exit, creal3 light_direction) {
  return chain_constraint_toward(exit, -light_direction, creal3(LUCENT_CREAL(0.0)), creal3(LUCENT_CREAL(0.0)));
}

// Point light at `light_position`: o must equal v = normalize(light_position - e), which moves with e:
// d v = -(I - v v^T) d e / |light_position - e|.
LUCENT_INLINE ChainConstraint chain_constraint_point(ChainExit exit, creal3 light_position) {
  creal3 to_light = light_position - exit.e;
  creal r = length(to_light);
  creal3 v = to_light / r;
  creal3 dv_u = -(exit.de_u - v * dot(v, exit.de_u)) / r, dv_v = -(exit.de_v - v * dot(v, exit.de_v)) / r;
  return chain_constraint_toward(exit, v, dv_u, dv_v);
}

// The radiance the chain delivers per unit of the light's irradiance (directional) or of I / r^2 (point light),
// before the medium's transmittance along the chain: eta^2 T prod F / |det J|.
LUCENT_INLINE creal chain_radiance_factor(ChainExit exit, ChainConstraint c, creal eta) {
  creal det = abs(chain_jacobian_determinant(c));
  return det > LUCENT_CREAL(0.0) ? eta * eta * exit.transmittance * exit.reflectance / det : LUCENT_CREAL(0.0);
}

// ---- chains from a boundary point ---------------------------------------------------------------------------
// The solvers move the chain's vertex on the boundary itself: the exit point e (where the light refracts in) for an
// unreflected chain, with the light's refracted ray from e required to pass through x. Every light ray that meets the
// boundary from outside refracts, so this parametrization has no total internal reflection to step around (the
// direction parametrization from x has, wherever the chain from x meets the boundary beyond the critical angle), and
// a Newton step walks across the mesh's triangles (chain_walk_step) with no ray to trace.

// The light arriving at boundary point e along `direction`, with its derivatives along the two coordinates of e's
// tangent plane (t_u, t_v) and of its direction (zero for a directional light).
LUCENT_INLINE ChainState chain_start_at(creal3 e, creal3 direction, creal3 t_u, creal3 t_v, creal3 ddirection_u,
                                        creal3 ddirection_v) {
  ChainState s;
  s.y = e;
  s.d = direction;
  s.dy_u = t_u;
  s.dy_v = t_v;
  s.dd_u = ddirection_u;
  s.dd_v = ddirection_v;
  s.path_length = LUCENT_CREAL(0.0);
  s.reflectance = LUCENT_CREAL(1.0);
  return s;
}

// Refraction into the medium (relative index eta) at the vertex the state is at; false (in `refracts`) when the
// light meets the boundary from inside.
struct ChainEntry {
  bool refracts;
  ChainState state;
};
LUCENT_INLINE ChainEntry chain_refract_in(ChainState s, ChainVertex vertex, creal eta) {
  ChainEntry entry;
  creal3 n = vertex.shading_normal;  // out of the object: the side the light comes from
  creal3 dn_u = chain_normal_change(vertex, s.dy_u), dn_v = chain_normal_change(vertex, s.dy_v);
  creal ratio = LUCENT_CREAL(1.0) / eta;
  creal cos_i = -dot(s.d, n);
  creal sin2_t = ratio * ratio * (LUCENT_CREAL(1.0) - cos_i * cos_i);
  entry.refracts = cos_i > LUCENT_CREAL(0.0) && sin2_t < LUCENT_CREAL(1.0);  // (eta < 1 reflects some totally)
  creal cos_t = sqrt(max(LUCENT_CREAL(0.0), LUCENT_CREAL(1.0) - sin2_t));
  creal dcos_i_u = -(dot(s.dd_u, n) + dot(s.d, dn_u)), dcos_i_v = -(dot(s.dd_v, n) + dot(s.d, dn_v));
  creal safe_cos_t = max(cos_t, LUCENT_CREAL(1e-12));
  creal dcos_t_u = ratio * ratio * cos_i * dcos_i_u / safe_cos_t;
  creal dcos_t_v = ratio * ratio * cos_i * dcos_i_v / safe_cos_t;
  s.dd_u = ratio * s.dd_u + (ratio * dcos_i_u - dcos_t_u) * n + (ratio * cos_i - cos_t) * dn_u;
  s.dd_v = ratio * s.dd_v + (ratio * dcos_i_v - dcos_t_v) * n + (ratio * cos_i - cos_t) * dn_v;
  s.d = ratio * s.d + (ratio * cos_i - cos_t) * n;
  s.path_length = LUCENT_CREAL(0.0);
  entry.state = s;
  return entry;
}

// How the leg (s.y, s.d) misses x: the components of cross(d, x - y) (length: the miss distance) in a basis of the
// plane perpendicular to d, their Jacobian (the basis held fixed: exact at a solution), how far along the leg x lies,
// and x's distance from the leg's start.
struct ChainMiss {
  creal2 residual;
  creal2 j_u, j_v;
  creal along;
  creal distance;
};
LUCENT_INLINE ChainMiss chain_miss(ChainState s, creal3 x) {
  ChainBasis b = chain_basis(s.d);
  creal3 q = x - s.y;
  creal3 r = cross(s.d, q);
  creal3 dr_u = cross(s.dd_u, q) - cross(s.d, s.dy_u), dr_v = cross(s.dd_v, q) - cross(s.d, s.dy_v);
  ChainMiss m;
  m.residual = creal2(dot(b.u, r), dot(b.v, r));
  m.j_u = creal2(dot(b.u, dr_u), dot(b.v, dr_u));
  m.j_v = creal2(dot(b.u, dr_v), dot(b.v, dr_v));
  m.along = dot(q, s.d);
  m.distance = length(q);
  return m;
}

// An orthonormal basis of triangle (p0, p1, p2)'s plane: the coordinates of a step on it.
LUCENT_INLINE ChainBasis chain_plane_basis(creal3 p0, creal3 p1, creal3 p2) {
  creal3 t = normalize(p1 - p0);
  ChainBasis b;
  b.u = t;
  b.v = normalize(cross(cross(t, p2 - p0), t));
  return b;
}

// ---- walking on the mesh -------------------------------------------------------------------------------------
// A step from point p of a triangle, in its plane, continues across an edge onto the neighbouring triangle, unfolded
// about the shared edge (its length and its angle with the edge kept), as far as it goes.

// Where the segment from p (in the triangle) to p + delta leaves triangle (p0, p1, p2): `edge` 0 (p0 p1), 1 (p1 p2)
// or 2 (p2 p0) at the fraction t of delta, or -1 when p + delta is inside.
struct ChainWalkExit {
  int edge;
  creal t;
};
LUCENT_INLINE ChainWalkExit chain_walk_exit(creal3 p0, creal3 p1, creal3 p2, creal3 p, creal3 delta) {
  creal3 e1 = p1 - p0, e2 = p2 - p0, N = cross(e1, e2);
  creal area2 = dot(N, N);
  creal3 g1 = cross(e2, N) / area2, g2 = cross(N, e1) / area2;
  // Barycentrics (b0, b1, b2) at p and their change along delta.
  creal b1 = dot(p - p0, g1), b2 = dot(p - p0, g2), b0 = LUCENT_CREAL(1.0) - b1 - b2;
  creal d1 = dot(delta, g1), d2 = dot(delta, g2), d0 = -d1 - d2;
  ChainWalkExit exit;
  exit.edge = -1;
  exit.t = LUCENT_CREAL(1.0);
  // Edge k is opposite corner k + 2 (mod 3): edge 0 (p0 p1) where b2 = 0, edge 1 (p1 p2) where b0 = 0, edge 2 where b1 = 0.
  if (d2 < LUCENT_CREAL(0.0) && -b2 / d2 < exit.t) exit.t = max(LUCENT_CREAL(0.0), -b2 / d2), exit.edge = 0;
  if (d0 < LUCENT_CREAL(0.0) && -b0 / d0 < exit.t) exit.t = max(LUCENT_CREAL(0.0), -b0 / d0), exit.edge = 1;
  if (d1 < LUCENT_CREAL(0.0) && -b1 / d1 < exit.t) exit.t = max(LUCENT_CREAL(0.0), -b1 / d1), exit.edge = 2;
  return exit;
}

// The rest of a step, `delta`, carried across the edge from a (to b) from the plane with unit normal n_from onto the
// plane with unit normal n_to: its component along the edge kept, the one across it turned into the new plane.
LUCENT_INLINE creal3 chain_unfold(creal3 delta, creal3 a, creal3 b, creal3 n_from, creal3 n_to) {
  creal3 edge = normalize(b - a);
  creal3 across_from = cross(n_from, edge), across_to = cross(n_to, edge);
  // Both `across` vectors point to the same side of the edge when the normals are consistently oriented: the step
  // leaves the first triangle on one side and enters the second on the other, so the sign follows dot(delta, .).
  creal along = dot(delta, edge), across = dot(delta, across_from);
  return along * edge + across * across_to;
}

// ---- Newton's method on a chain's coordinates -----------------------------------------------------------------
// One controller for every parametrization (boundary points, a direction from x): the caller evaluates the chain at
// the current point and passes whether it was valid and its relative residual; the controller judges it. Steps are
// limited to `max_step` and backtracked (halved) when the residual does not decrease or the chain becomes invalid; a
// solve gives up when backtracking falls below kChainSmallestStep, or when it is still far from a solution (a
// relative residual above kChainFarResidual) kChainPatience evaluations after its first valid chain: where no chain
// exists (behind the boundary's terminator) Newton creeps toward the edge of the light's reach. A chain missed this
// way is left to manifold sampling, which counts every chain.
LUCENT_CONST float kChainSmallestStep = 1.0f / 16.0f;
LUCENT_CONST int kChainPatience = 6;
LUCENT_CONST float kChainFarResidual = 0.1f;

struct ChainNewton {
  creal fraction;       // of the step from the good point to take next
  creal residual_good;  // the relative residual at the good point
  int evaluations;      // since the first valid chain
  bool accepted;        // the point just evaluated became the good point: take a fresh step from it
  bool have_good, converged, failed;
};

LUCENT_INLINE ChainNewton chain_newton_start() {
  ChainNewton c;
  c.fraction = LUCENT_CREAL(1.0);
  c.residual_good = LUCENT_CREAL(0.0);
  c.evaluations = 0;
  c.accepted = false;
  c.have_good = false;
  c.converged = false;
  c.failed = false;
  return c;
}

LUCENT_INLINE ChainNewton chain_newton_backtrack(ChainNewton c) {
  c.accepted = false;
  if (!c.have_good || c.fraction <= LUCENT_CREAL(kChainSmallestStep)) {
    c.failed = true;
    return c;
  }
  c.fraction *= LUCENT_CREAL(0.5);
  return c;
}

// The verdict on the point just evaluated. relative_residual: |residual| in the units the tolerance is stated in (an
// angle). When `accepted`, the caller computes a fresh Newton step at this point (chain_newton_step2 or _step4) and
// takes it whole; otherwise it takes `fraction` of the last step from the good point.
LUCENT_INLINE ChainNewton chain_newton_judge(ChainNewton c, bool valid, creal relative_residual, creal tolerance) {
  c.accepted = false;
  if (c.have_good) c.evaluations += 1;
  if (c.evaluations >= kChainPatience && c.residual_good > LUCENT_CREAL(kChainFarResidual)) {
    c.failed = true;
    return c;
  }
  if (!valid) return chain_newton_backtrack(c);
  if (relative_residual < tolerance) {
    c.converged = true;
    return c;
  }
  if (c.have_good && relative_residual >= c.residual_good) return chain_newton_backtrack(c);
  c.fraction = LUCENT_CREAL(1.0);
  c.residual_good = relative_residual;
  c.have_good = true;
  c.accepted = true;
  return c;
}

// The Newton step of two equations in two unknowns, J step = -residual (J's columns j_u, j_v), at most max_step
// long; `ok` false when J is singular.
struct ChainStep2 {
  bool ok;
  creal2 step;
};
LUCENT_INLINE ChainStep2 chain_newton_step2(creal2 residual, creal2 j_u, creal2 j_v, creal max_step) {
  ChainStep2 s;
  creal det = j_u.x * j_v.y - j_v.x * j_u.y;
  s.ok = abs(det) > LUCENT_CREAL(0.0);
  s.step = creal2(LUCENT_CREAL(0.0));
  if (!s.ok) return s;
  s.step = creal2(-(j_v.y * residual.x - j_v.x * residual.y) / det, -(-j_u.y * residual.x + j_u.x * residual.y) / det);
  creal step_length = length(s.step);
  if (step_length > max_step) s.step *= max_step / step_length;
  return s;
}

// Four equations in four unknowns, in 2x2 blocks: [a_p a_q; b_p b_q] (step_p, step_q) = -(r_a, r_b), each block given
// by its columns, solved by Gaussian elimination with partial pivoting; step_p and step_q at most max_step long.
struct ChainStep4 {
  bool ok;
  creal2 step_p, step_q;
};
LUCENT_INLINE ChainStep4 chain_newton_step4(creal2 r_a, creal2 r_b, creal2 a_p_u, creal2 a_p_v, creal2 a_q_u,
                                            creal2 a_q_v, creal2 b_p_u, creal2 b_p_v, creal2 b_q_u, creal2 b_q_v,
                                            creal max_step) {
  // Rows: the equations (r_a.x, r_a.y, r_b.x, r_b.y); columns: the unknowns (p.u, p.v, q.u, q.v), and -r.
  creal m[4][5];
  m[0][0] = a_p_u.x, m[0][1] = a_p_v.x, m[0][2] = a_q_u.x, m[0][3] = a_q_v.x, m[0][4] = -r_a.x;
  m[1][0] = a_p_u.y, m[1][1] = a_p_v.y, m[1][2] = a_q_u.y, m[1][3] = a_q_v.y, m[1][4] = -r_a.y;
  m[2][0] = b_p_u.x, m[2][1] = b_p_v.x, m[2][2] = b_q_u.x, m[2][3] = b_q_v.x, m[2][4] = -r_b.x;
  m[3][0] = b_p_u.y, m[3][1] = b_p_v.y, m[3][2] = b_q_u.y, m[3][3] = b_q_v.y, m[3][4] = -r_b.y;
  ChainStep4 s;
  s.ok = true;
  s.step_p = creal2(LUCENT_CREAL(0.0));
  s.step_q = creal2(LUCENT_CREAL(0.0));
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    // loop bound: 3; the rows below the pivot's
    for (int row = col + 1; row < 4; ++row)
      if (abs(m[row][col]) > abs(m[pivot][col])) pivot = row;
    if (!(abs(m[pivot][col]) > LUCENT_CREAL(0.0))) {
      s.ok = false;
      return s;
    }
    for (int k = 0; k < 5; ++k) {
      creal t = m[col][k];
      m[col][k] = m[pivot][k];
      m[pivot][k] = t;
    }
    // loop bound: 3; the rows below the pivot's
    for (int row = col + 1; row < 4; ++row) {
      creal f = m[row][col] / m[col][col];
      // loop bound: 5; the columns of a row
      for (int k = col; k < 5; ++k) m[row][k] -= f * m[col][k];
    }
  }
  creal x[4];
  for (int row = 3; row >= 0; --row) {
    creal sum = m[row][4];
    // loop bound: 3; the unknowns already solved
    for (int k = row + 1; k < 4; ++k) sum -= m[row][k] * x[k];
    x[row] = sum / m[row][row];
  }
  s.step_p = creal2(x[0], x[1]);
  s.step_q = creal2(x[2], x[3]);
  creal longest = max(length(s.step_p), length(s.step_q));
  if (longest > max_step) {
    s.step_p *= max_step / longest;
    s.step_q *= max_step / longest;
  }
  return s;
}

// The direction w moved by coordinates (a, b) of its basis.
LUCENT_INLINE creal3 chain_direction_step(creal3 w, creal2 step) {
  ChainBasis basis = chain_basis(w);
  return normalize(w + step.x * basis.u + step.y * basis.v);
}

LUCENT_SHADER_END

#endif
