// trace.comp: the random-walk method: volumetric path tracing of the scene as the CPU reference `volpath` defines it
// (src/reference/volpath.cpp, docs/references.md), one or more paths per pixel and frame, accumulated while nothing
// changes. Homogeneous media and procedural fields behind smooth dielectric boundaries (Fresnel, total internal
// reflection), per-band Henyey-Greenstein phase functions with hero-band spectral MIS over the whole path, Lambertian
// opaque surfaces with diffuse interreflection, and next-event estimation of every light through the refracting
// boundary along every specular chain (boundary_light.glsl). Rays traverse the bounding volume hierarchy built on the CPU
// (methods/random_walk/triangle_bvh.h). The walk's steps are the shared ones of shared/volume_walk.h; dense
// media jump across spheres inside the medium (sphere_jump.glsl).
#include "common/frame.glsl"
#include "bssrdf/fresnel.h"
#include "lights/point_light.h"
#include "media/heterogeneous_field.h"
#include "shared/random.h"
#include "shared/sphere_walk.h"
#include "shared/specular_chain.h"
#include "shared/volume_walk.h"
#include "methods/random_walk/random_walk_io.h"

layout(local_size_x = LUCENT_WALK_POOL_GROUP, local_size_y = 1, local_size_z = 1) in;

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { RandomWalkGPU method; };
layout(std430, binding = LUCENT_BINDING_WALK_NODES) readonly buffer NodeBlock { BvhNodeGPU nodes[]; };
layout(std430, binding = LUCENT_BINDING_WALK_TRIANGLES) readonly buffer TriangleBlock { TriangleGPU triangles[]; };
layout(std430, binding = LUCENT_BINDING_WALK_OBJECTS) readonly buffer WalkObjectBlock { WalkObjectGPU walk_objects[]; };
layout(std430, binding = LUCENT_BINDING_WALK_SPHERES) readonly buffer SphereBlock { SphereWalkGPU spheres[]; };
layout(binding = LUCENT_TEX_WALK_DISTANCE) uniform sampler3D distance_grid;

const int kMaxShadowCrossings = 64;       // index-matched media a shadow ray crosses at most (as volpath)
const int kMaxTraversalSteps = 60000;     // BVH nodes one ray visits at most (under llvmpipe's 65,535 iterations)
const int kMaxRatioTrackingSteps = 60000; // tentative collisions of one transmittance estimate at most
// Self-intersection offsets relative to the largest coordinate involved (volpath: 1e-6 in double; the GPU
// intersects and rebuilds hit points in float, a few rounding steps of 6e-8 each).
const float kRelativeOffset = 2e-6f;
// Optical depth (to the nearest surface) under which every next-event estimate traces the light through the boundary;
// deeper, it runs with probability e^(kNextEventFullDepth - depth) (medium_next_event).
const float kNextEventFullDepth = 3.0f;

// ---- random numbers: one counter-based stream per (seed, pixel, sample) ---------------------------------------
uint rng_key = 0u, rng_count = 0u;
float rnd() {
  rng_count += 1u;
  return next_float(rng_key ^ pcg_hash(rng_count));
}

// Loop iterations this invocation has run: llvmpipe ends every loop of an invocation once their iterations
// together pass 65,535 (one counter per invocation, never reset), so an invocation starts another event only
// well under that, and a path that went past it is counted as unreliable.
uint loop_count = 0u;
// This invocation's work in the dispatch, added to the batch's counters at its end.
uint stat_traversals = 0u, stat_node_visits = 0u, stat_next_events = 0u, stat_next_event_traversals = 0u;

// Whether the driver's loop cap has ended this invocation's loops: a loop of dispatch.w (2) iterations, a count the
// compiler cannot unroll, then runs one at most. (The per-lane loop_count undercounts the driver's counter, which
// counts the iterations of the SIMD loop over 8 or 16 invocations at once.)
bool loops_were_cut() {
  uint n = 0u;
  // loop bound: checked; the probe of the cap: random_walk.cpp sets its count from kLlvmpipeLoopIterations
  for (uint i = 0u; i < method.dispatch.w; ++i) ++n;
  return n != method.dispatch.w;
}

float max3(vec3 v) { return max(v.x, max(v.y, v.z)); }
float mean3(vec3 v) { return (v.x + v.y + v.z) / 3.0f; }
float largest_abs(vec3 v) { return max3(abs(v)); }
float offset_at(vec3 p) { return kRelativeOffset * largest_abs(p); }

// ---- rays -------------------------------------------------------------------------------------------------------
struct Hit {
  float t;
  int object;    // -1: miss
  int triangle;  // index into triangles[]
  vec3 position, normal, geometric_normal;  // normal: interpolated, out of the object; geometric: on its side
  float offset;
};

// Slab test: the entry distance of the ray into the box, or a negative value when it misses within [0, t_max].
float box_entry(vec3 lower, vec3 upper, vec3 origin, vec3 inv_direction, float t_max) {
  vec3 t0 = (lower - origin) * inv_direction, t1 = (upper - origin) * inv_direction;
  vec3 near = min(t0, t1), far = max(t0, t1);
  float enter = max(max(near.x, near.y), max(near.z, 0.0f));
  float leave = min(min(far.x, far.y), min(far.z, t_max));
  return enter <= leave ? enter : -1.0f;
}

// The closest hit in (t_min, t_max].
Hit trace(vec3 origin, vec3 direction, float t_max, float t_min) {
  Hit hit;
  hit.object = -1;
  hit.triangle = -1;
  hit.t = t_max;
  vec3 inv_direction = 1.0f / mix(direction, vec3(1e-30f), lessThan(abs(direction), vec3(1e-30f)));
  int best = -1;
  vec2 best_uv = vec2(0.0f);
  int stack[64];
  int depth = 0, node = 0;
  ++stat_traversals;
  if (box_entry(nodes[0].lower.xyz, nodes[0].upper.xyz, origin, inv_direction, t_max) < 0.0f) return hit;
  // loop bound: checked; every iteration counts in loop_count, and an invocation starts another event only while loop_count stays under method.dispatch.y (random_walk.cpp budgets it well under kLlvmpipeLoopIterations)
  for (int step = 0; step < kMaxTraversalSteps; ++step) {
    ++loop_count;
    ++stat_node_visits;
    BvhNodeGPU n = nodes[node];
    int count = floatBitsToInt(n.upper.w);
    if (count > 0) {
      int first = floatBitsToInt(n.lower.w);
      // loop bound: checked; every iteration counts in loop_count, and an invocation starts another event only while loop_count stays under method.dispatch.y, which random_walk.cpp budgets well under kLlvmpipeLoopIterations
      for (int i = first; i < first + count; ++i) {
        ++loop_count;
        TriangleGPU tri = triangles[i];
        vec3 p = cross(direction, tri.e2.xyz);
        float det = dot(tri.e1.xyz, p);
        if (det == 0.0f) continue;
        float inv_det = 1.0f / det;
        vec3 s = origin - tri.p0.xyz;
        float u = dot(s, p) * inv_det;
        if (u < 0.0f || u > 1.0f) continue;
        vec3 q = cross(s, tri.e1.xyz);
        float v = dot(direction, q) * inv_det;
        if (v < 0.0f || u + v > 1.0f) continue;
        float t = dot(tri.e2.xyz, q) * inv_det;
        if (t > t_min && t <= hit.t) hit.t = t, best = i, best_uv = vec2(u, v);
      }
    } else {
      int left = node + 1, right = floatBitsToInt(n.lower.w);
      float t_left = box_entry(nodes[left].lower.xyz, nodes[left].upper.xyz, origin, inv_direction, hit.t);
      float t_right = box_entry(nodes[right].lower.xyz, nodes[right].upper.xyz, origin, inv_direction, hit.t);
      if (t_left >= 0.0f && t_right >= 0.0f) {
        bool left_first = t_left <= t_right;
        if (depth < 64) stack[depth++] = left_first ? right : left;
        node = left_first ? left : right;
        continue;
      }
      if (t_left >= 0.0f || t_right >= 0.0f) {
        node = t_left >= 0.0f ? left : right;
        continue;
      }
    }
    if (depth == 0) break;
    node = stack[--depth];
  }
  if (best < 0) return hit;
  TriangleGPU tri = triangles[best];
  float u = best_uv.x, v = best_uv.y;
  hit.object = floatBitsToInt(tri.p0.w);
  hit.triangle = best;
  hit.position = tri.p0.xyz + u * tri.e1.xyz + v * tri.e2.xyz;
  hit.normal = normalize((1.0f - u - v) * tri.n0.xyz + u * tri.n1.xyz + v * tri.n2.xyz);
  vec3 ng = normalize(cross(tri.e1.xyz, tri.e2.xyz));
  hit.geometric_normal = dot(ng, hit.normal) < 0.0f ? -ng : ng;
  float magnitude = max(max(largest_abs(tri.p0.xyz), largest_abs(tri.p0.xyz + tri.e1.xyz)),
                        max(largest_abs(tri.p0.xyz + tri.e2.xyz), largest_abs(hit.position)));
  hit.offset = kRelativeOffset * magnitude;
  return hit;
}
Hit trace_from_surface(vec3 origin, vec3 direction, float t_max) {
  return trace(origin, direction, t_max, offset_at(origin));
}

// ---- media ------------------------------------------------------------------------------------------------------
bool translucent(int object) { return walk_objects[object].sigma_s.w > 0.5f; }
float eta_of(int object) { return walk_objects[object].sigma_a.w; }
bool heterogeneous(int object) { return int(walk_objects[object].g.w) != kFieldNone; }
vec3 sigma_a_of(int object) { return walk_objects[object].sigma_a.xyz; }
vec3 sigma_s_of(int object) { return walk_objects[object].sigma_s.xyz; }
vec3 sigma_t_of(int object) { return sigma_a_of(object) + sigma_s_of(object); }
float multiplier(int object, vec3 x) {
  WalkObjectGPU o = walk_objects[object];
  return field_multiplier(int(o.g.w), x, o.lower.xyz, o.upper.xyz, o.lower.w, o.upper.w);
}

// Transmittance between a and b inside `object`: exact when homogeneous, ratio tracking against the largest band
// majorant otherwise (unbiased, in [0, 1]).
vec3 transmittance(int object, vec3 a, vec3 b) {
  float length_ab = length(b - a);
  if (!heterogeneous(object)) return exp(-sigma_t_of(object) * length_ab);
  float mu = max3(walk_objects[object].majorant.xyz);
  vec3 direction = (b - a) / max(length_ab, 1e-30f), sigma_t = sigma_t_of(object);
  vec3 T = vec3(1.0f);
  float t = free_flight(mu, rnd());
  // loop bound: checked; every iteration counts in loop_count, and an invocation starts another event only while loop_count stays under method.dispatch.y (random_walk.cpp budgets it well under kLlvmpipeLoopIterations)
  for (int i = 0; i < kMaxRatioTrackingSteps && t < length_ab; ++i) {
    ++loop_count;
    T *= max(vec3(0.0f), 1.0f - multiplier(object, a + t * direction) * sigma_t / mu);
    if (max3(T) <= 0.0f) break;
    t += free_flight(mu, rnd());
  }
  return T;
}

// The straight shadow ray from `origin` (outside every medium): opaque surfaces and refracting boundaries block
// it, index-matched media attenuate it. One trace call for where the ray enters a medium and where it leaves it (the
// shader compiler inlines every call).
vec3 shadow_transmittance(vec3 origin, vec3 direction, float t_max) {
  vec3 T = vec3(1.0f), entered = origin;
  int inside = -1;
  // loop bound: checked; 2 kMaxShadowCrossings (128) (each iteration counted in loop_count, budgeted by random_walk.cpp)
  for (int k = 0; k < 2 * kMaxShadowCrossings; ++k) {
    ++loop_count;
    Hit hit = trace_from_surface(origin, direction, t_max);
    if (inside < 0) {
      if (hit.object < 0) return T;
      if (!translucent(hit.object) || eta_of(hit.object) != 1.0f) return vec3(0.0f);
      inside = hit.object, entered = hit.position;
    } else {
      if (hit.object != inside) return vec3(0.0f);
      T *= transmittance(inside, entered, hit.position);
      if (max3(T) <= 0.0f) return T;
      inside = -1;
    }
    origin = hit.position;
    t_max -= hit.t;
  }
  return vec3(0.0f);
}

// ---- lights -----------------------------------------------------------------------------------------------------
int light_medium(int l) { return method.light_media[l / 4][l % 4]; }

vec3 point_intensity(LightGPU light, vec3 direction) {
  vec3 I = light.power.rgb;
  if (int(light.position.w) == LUCENT_LIGHT_SPOT) I *= spot_falloff(dot(direction, light.axis.xyz), light.power.w, light.axis.w);
  return I;
}

// ---- the distance bound (sphere jumps, short flights, deep next-event estimates) --------------------------------
// A lower bound of the distance from x to every surface: the distance grid's value at the nearest cell centre
// minus the distance to it (the distance is 1-Lipschitz), minus how far the surfaces moved since the grid was built.
float surface_distance_bound(vec3 x) {
  vec3 cells = vec3(method.distance_size.xyz);
  vec3 u = (x - method.distance_lower.xyz) / method.distance_lower.w;
  ivec3 cell = ivec3(clamp(floor(u), vec3(0.0f), cells - 1.0f));
  vec3 centre = method.distance_lower.xyz + (vec3(cell) + 0.5f) * method.distance_lower.w;
  return texelFetch(distance_grid, cell, 0).r - length(x - centre) - method.jump_bound.x;
}

#include "methods/random_walk/shaders/boundary_light.glsl"

// Light in-scattered at medium vertex x of `object` toward -path_dir (phase functions per band): every light outside
// the medium through the boundary (boundary_light.glsl); the point lights inside it along the flights instead.
vec3 medium_next_event(int object, vec3 x, vec3 path_dir) {
  ++stat_next_events;
  uint traversals_before = stat_traversals;
  vec3 g = walk_objects[object].g.xyz;
  vec3 L = vec3(0.0f), L_outside = vec3(0.0f);
  // Its own random numbers: the path's do not depend on how many the estimate draws.
  uint path_key = rng_key, path_count = rng_count;
  rng_key = pcg_hash(rng_key ^ pcg_hash(rng_count ^ 0x2545f491u));
  rng_count = 0u;
  // Light from outside the medium crosses at least the distance to the nearest surface inside it, so in a
  // homogeneous medium its transmittance is at most e^-depth, depth that distance (the grid's bound) times the
  // smallest extinction. Deeper than kNextEventFullDepth the estimate through the boundary runs with probability
  // e^(kNextEventFullDepth - depth) and counts divided by it (Russian roulette: unbiased, the weighted estimate stays
  // under e^-kNextEventFullDepth of an unattenuated one).
  float survival = 1.0f;
  if (method.jump_bound.y > 0.5f && !heterogeneous(object)) {
    vec3 sigma_t = sigma_t_of(object);
    float depth = min(sigma_t.x, min(sigma_t.y, sigma_t.z)) * surface_distance_bound(x);
    if (depth > kNextEventFullDepth) survival = exp(kNextEventFullDepth - depth);
  }
  bool through_boundary = survival >= 1.0f || rnd() < survival;
  // loop bound: checked; at most LUCENT_MAX_LIGHTS lights per call, each counted in loop_count (budgeted by random_walk.cpp)
  for (int l = 0; l < frame.light_counts.x; ++l) {
    ++loop_count;
    LightGPU light = frame.lights[l];
    bool point = int(light.position.w) != LUCENT_LIGHT_DIRECTIONAL;
    // A point light inside a medium: this one's are estimated along the flights (interior_lights_along), another's
    // do not reach here.
    if (point && light_medium(l) >= 0) continue;
    if (through_boundary) L_outside += light_through_boundary(object, x, path_dir, l);
  }
  L += L_outside / survival;
  rng_key = path_key, rng_count = path_count;
  stat_next_event_traversals += stat_traversals - traversals_before;
  return L;
}

// Direct light on an opaque Lambertian point (shadow rays through index-matched media).
vec3 lambertian_next_event(Hit hit, vec3 n, vec3 albedo) {
  vec3 L = vec3(0.0f);
  vec3 origin = hit.position + hit.offset * n;
  // loop bound: checked; at most LUCENT_MAX_LIGHTS lights per call, each counted in loop_count (budgeted by random_walk.cpp)
  for (int l = 0; l < frame.light_counts.x; ++l) {
    ++loop_count;
    LightGPU light = frame.lights[l];
    bool directional = int(light.position.w) == LUCENT_LIGHT_DIRECTIONAL;
    vec3 to_light = directional ? -light.position.xyz : light.position.xyz - hit.position;
    float d = directional ? 1.0f : length(to_light);
    to_light /= d;
    float cos_l = dot(n, to_light);
    if (cos_l <= 0.0f) continue;
    vec3 E = directional ? light.power.rgb : point_intensity(light, -to_light) / (d * d);
    float t_max = directional ? 1e30f : d - offset_at(light.position.xyz);
    L += albedo / kWalkPi * E * cos_l * shadow_transmittance(origin, to_light, t_max);
  }
  return L;
}

// ---- the path ---------------------------------------------------------------------------------------------------
// Hero-band spectral MIS over the whole path (volpath's PathState): contributions are throughput / mean(r_u).
vec3 path_origin, path_direction, path_throughput, path_r_u, path_radiance;
int path_hero, path_medium, path_events, path_scatterings;
uint path_steps;
uint path_region;  // its results region (0 or 1): its frame's, whose sphere-walk banks it reads
uint path_jump_start, path_jumps;

vec3 path_weight() { return path_throughput / mean3(path_r_u); }
void path_add(vec3 incoming) { path_radiance += path_weight() * incoming; }

bool roulette() {
  if (++path_events < method.limits.y) return true;
  float survive = min(1.0f, max3(path_weight()));
  if (survive >= 1.0f) return true;
  if (survive <= 0.0f || rnd() >= survive) return false;
  path_throughput /= survive;
  return true;
}

bool leave_or_reflect(Hit boundary) {
  float eta = eta_of(path_medium);
  float F = fresnel_reflectance(1.0f / eta, abs(dot(path_direction, boundary.normal)));
  path_origin = boundary.position;
  if (rnd() < F) {
    path_direction = mirror_direction(path_direction, boundary.normal);
    path_origin -= boundary.offset * boundary.geometric_normal;
  } else {
    path_direction = refract_direction(path_direction, boundary.normal, 1.0f / eta);
    path_throughput *= eta * eta;
    path_origin += boundary.offset * boundary.geometric_normal;
    path_medium = -1;
  }
  return roulette();
}


// ---- sphere jumps (docs/methods/random-walk.md) -----------------------------------------------------------------
// The collision a jump's record represents, for its next-event estimate (n times the weight after it).
vec3 jump_vertex, jump_vertex_direction, jump_vertex_weight;

// Whether a point light lies inside `object` (light_media: the medium of each point light).
bool has_interior_lights(int object) {
  // loop bound: checked; at most LUCENT_MAX_LIGHTS lights (each counted in loop_count, budgeted by random_walk.cpp)
  for (int l = 0; l < frame.light_counts.x; ++l) {
    ++loop_count;
    if (int(frame.lights[l].position.w) != LUCENT_LIGHT_DIRECTIONAL && light_medium(l) == object) return true;
  }
  return false;
}

// At scattering vertex x (its next-event estimate done): jump across the largest sphere of the levels that lies
// inside the medium, from a record of the frame's bank, turned toward a direction sampled from the phase function
// with a uniform azimuth. The collisions inside count through the record's one vertex (n times its next-event
// estimate); absorption and the other bands through the weights of shared/sphere_walk.h. False: no sphere fits.
bool sphere_jump(vec3 x) {
  WalkObjectGPU o = walk_objects[path_medium];
  int bank = int(o.majorant.w);
  if ((method.samples.w & uint(LUCENT_WALK_SPHERE_JUMPS)) == 0u || bank < 0 || method.jump_bound.y < 0.5f ||
      method.limits.z > 0 || int(o.g.w) != kFieldNone || has_interior_lights(path_medium))
    return false;
  vec3 sigma_s = o.sigma_s.xyz, sigma_t = o.sigma_a.xyz + sigma_s;
  float sigma_hero = sigma_t[path_hero];
  // 1% inside the bound: the exit point stays inside the medium after float rounding.
  float optical_room = 0.99f * surface_distance_bound(x) * sigma_hero;
  int level = -1;
  for (int l = 0; l < kSphereJumpLevelCount; ++l) {
    ++loop_count;
    if (sphere_jump_level_radius(l) <= optical_room && path_jumps < uint(method.jump_records[l / 4][l % 4])) level = l;
  }
  if (level < 0) return false;
  uint count = uint(method.jump_records[level / 4][level % 4]);
  SphereWalkGPU record = spheres[((int(path_region) * method.jump_info.x + bank) * kSphereJumpLevelCount + level) *
                                     method.distance_size.w +
                                 int((path_jump_start + path_jumps) % count)];
  ++path_jumps;
  ++path_steps;
  // The canonical frame: +z toward a direction from the phase function, a uniform azimuth about it.
  vec3 w = sample_hg(path_direction, o.g.x, rnd(), rnd());
  mat3 basis = walk_frame(w);
  float phi = 2.0f * kWalkPi * rnd(), c = cos(phi), s = sin(phi);
  mat3 turn = mat3(c * basis[0] + s * basis[1], -s * basis[0] + c * basis[1], w);
  float radius = sphere_jump_level_radius(level) / sigma_hero;  // [scene units]
  float n = record.exit_dir.w;
  jump_vertex_weight = vec3(0.0f);
  if (n >= 1.0f) {
    float j = record.vertex_dir.w;
    vec3 throughput_v = path_throughput * sphere_jump_throughput(j, record.vertex.w / sigma_hero, sigma_s, sigma_t, sigma_hero);
    vec3 r_u_v = path_r_u * sphere_jump_ratio(j, record.vertex.w / sigma_hero, sigma_t, sigma_hero);
    jump_vertex = x + radius * (turn * record.vertex.xyz);
    jump_vertex_direction = normalize(turn * record.vertex_dir.xyz);
    jump_vertex_weight = n * throughput_v / mean3(r_u_v);
  }
  path_throughput *= sphere_jump_throughput(n, record.exit.w / sigma_hero, sigma_s, sigma_t, sigma_hero);
  path_r_u *= sphere_jump_ratio(n, record.exit.w / sigma_hero, sigma_t, sigma_hero);
  path_origin = x + radius * (turn * record.exit.xyz);
  path_direction = normalize(turn * record.exit_dir.xyz);
  return true;
}

// The light of the point lights inside the path's medium in-scattered along the flight about to leave path_origin
// in path_direction, up to the boundary at t_b: per light one point of the flight with density proportional to
// 1 / |x(t) - light|^2 (equiangular sampling, Kulla and Fajardo 2012; volpath's interior_lights_along).
vec3 interior_lights_along(int object, float t_b) {
  vec3 L = vec3(0.0f), g = walk_objects[object].g.xyz;
  // loop bound: checked; at most LUCENT_MAX_LIGHTS lights (each counted in loop_count, budgeted by random_walk.cpp)
  for (int l = 0; l < frame.light_counts.x; ++l) {
    ++loop_count;
    LightGPU light = frame.lights[l];
    if (int(light.position.w) == LUCENT_LIGHT_DIRECTIONAL || light_medium(l) != object) continue;
    vec3 x_l = light.position.xyz;
    float delta = dot(x_l - path_origin, path_direction);
    float h = length(x_l - (path_origin + delta * path_direction));
    if (!(h > 0.0f)) continue;
    float theta_a = atan(-delta / h), theta_b = atan((t_b - delta) / h);
    if (!(theta_b > theta_a)) continue;
    float t = delta + h * tan(theta_a + rnd() * (theta_b - theta_a));
    float pdf = h / ((theta_b - theta_a) * (h * h + (t - delta) * (t - delta)));
    vec3 x = path_origin + t * path_direction;
    vec3 to_light = x_l - x;
    float d = length(to_light);
    if (!(d > 0.0f) || trace(x, to_light / d, d, 0.0f).object >= 0) continue;
    vec3 light_dir = -to_light / d;
    vec3 sigma_s = heterogeneous(object) ? min(multiplier(object, x), 1.0f) * sigma_s_of(object) : sigma_s_of(object);
    L += transmittance(object, path_origin, x) * sigma_s * hg_phase_between(light_dir, -path_direction, g) *
         point_intensity(light, light_dir) / (d * d) * transmittance(object, x_l, x) / pdf;
  }
  return L;
}

// A scattering vertex at x: next-event estimation, then a sphere jump (with the estimate at the collision its record
// represents) or the hero band's phase sampling. The estimates share one call (the shader compiler inlines each).
bool scatter(vec3 x) {
  vec3 nee_x = x, nee_direction = path_direction, nee_weight = path_weight();
  bool jumped = false;
  // loop bound: checked; 2 (the vertex, then a jump's collision) (each iteration counted in loop_count, budgeted by random_walk.cpp)
  for (int k = 0; k < 2; ++k) {
    ++loop_count;
    path_radiance += nee_weight * medium_next_event(path_medium, nee_x, nee_direction);
    if (k == 1) break;
    if (method.limits.z > 0 && ++path_scatterings >= method.limits.z) return false;
    jumped = sphere_jump(x);
    if (!jumped || max3(jump_vertex_weight) <= 0.0f) break;
    nee_x = jump_vertex, nee_direction = jump_vertex_direction, nee_weight = jump_vertex_weight;
  }
  if (jumped) return roulette();
  vec3 g = walk_objects[path_medium].g.xyz;
  vec3 next = sample_hg(path_direction, g[path_hero], rnd(), rnd());
  vec3 phase = hg_phase_between(next, path_direction, g);
  path_throughput *= phase / phase[path_hero];
  path_r_u *= phase / phase[path_hero];
  path_origin = x;
  path_direction = next;
  return roulette();
}

// Delta tracking against the band majorants with null collisions (volpath's delta_track). 0 absorbed,
// 1 scattered at x, 2 reached the boundary.
int delta_track(float boundary_t, out vec3 x) {
  int object = path_medium;
  vec3 sigma_maj = walk_objects[object].majorant.xyz, sigma_t = sigma_t_of(object), sigma_s = sigma_s_of(object);
  float mu = sigma_maj[path_hero];
  float t = 0.0f;
  x = path_origin;
  // loop bound: checked; every iteration counts in loop_count, and an invocation starts another event only while loop_count stays under method.dispatch.y (random_walk.cpp budgets it well under kLlvmpipeLoopIterations)
  for (int i = 0; i < kMaxRatioTrackingSteps; ++i) {
    ++loop_count;
    float dt = free_flight(mu, rnd());
    if (t + dt >= boundary_t) {
      vec3 T = exp(-sigma_maj * (boundary_t - t));
      path_throughput *= T / T[path_hero];
      path_r_u *= T / T[path_hero];
      return 2;
    }
    t += dt;
    ++path_steps;
    x = path_origin + t * path_direction;
    float m = multiplier(object, x);
    vec3 sigma_t_x = m * sigma_t, sigma_s_x = min(m, 1.0f) * sigma_s;
    vec3 sigma_a_x = sigma_t_x - sigma_s_x;
    vec3 sigma_n = max(vec3(0.0f), sigma_maj - sigma_t_x);
    vec3 T = exp(-sigma_maj * dt);
    float u = rnd() * mu;
    if (u < sigma_a_x[path_hero]) return 0;
    if (u < sigma_a_x[path_hero] + sigma_s_x[path_hero]) {
      float pdf = T[path_hero] * sigma_s_x[path_hero];
      path_throughput *= T * sigma_s_x / pdf;
      path_r_u *= T * sigma_s_x / pdf;
      return 1;
    }
    float pdf = T[path_hero] * sigma_n[path_hero];
    if (!(pdf > 0.0f)) return 0;
    path_throughput *= T * sigma_n / pdf;
    path_r_u *= T * sigma_n / pdf;
    if (max3(path_throughput) <= 0.0f) return 0;
  }
  return 0;  // the step bound: the path ends (a bias below any measurable level; see the method's doc)
}

// A free flight in the medium (delta tracking when heterogeneous): scatter, be absorbed, or reach the boundary. One
// trace and one scatter call (the shader compiler inlines every call).
bool medium_step() {
  int object = path_medium;
  ++path_steps;
  // The point lights inside the medium, along this flight (not past the last scattering event allowed), with their
  // own random numbers as the next-event estimates'.
  if ((method.limits.z == 0 || path_scatterings < method.limits.z) && has_interior_lights(object)) {
    Hit wall = trace(path_origin, path_direction, 1e30f, 0.0f);
    if (wall.object >= 0) {
      uint path_key = rng_key, path_count = rng_count;
      rng_key = pcg_hash(rng_key ^ pcg_hash(rng_count ^ 0x6a09e667u));
      rng_count = 0u;
      path_add(interior_lights_along(object, wall.t));
      rng_key = path_key, rng_count = path_count;
    }
  }
  bool field = heterogeneous(object);
  vec3 sigma_t = sigma_t_of(object);
  float t = field ? 1e30f : free_flight(sigma_t[path_hero], rnd());
  // A flight shorter than the distance grid's bound on the nearest surface cannot reach the boundary: no ray.
  Hit boundary;
  if (!field && method.jump_bound.y > 0.5f && t < surface_distance_bound(path_origin)) {
    boundary.object = -1;
    boundary.t = t;
  } else {
    boundary = trace(path_origin, path_direction, t, 0.0f);
  }
  vec3 x = path_origin + t * path_direction;
  int flight;  // 0 absorbed, 1 scattered at x, 2 reached the boundary
  if (field) {
    if (boundary.object < 0) return false;
    flight = delta_track(boundary.t, x);
  } else if (boundary.object < 0) {
    WalkObjectGPU o = walk_objects[object];
    if (isinf(t) || any(lessThan(x, o.mesh_lower.xyz)) || any(greaterThan(x, o.mesh_upper.xyz))) return false;
    vec3 attenuation = exp(-sigma_t * t);
    vec3 pdf = sigma_t * attenuation;
    path_throughput *= sigma_s_of(object) * attenuation / pdf[path_hero];
    path_r_u *= pdf / pdf[path_hero];
    flight = 1;
  } else {
    vec3 attenuation = exp(-sigma_t * boundary.t);
    path_throughput *= attenuation / attenuation[path_hero];
    path_r_u *= attenuation / attenuation[path_hero];
    flight = 2;
  }
  if (flight == 0) return false;
  if (flight == 1) return scatter(x);
  return leave_or_reflect(boundary);
}

bool surface_step(int bounce, Hit hit) {
  if (hit.object < 0) {
    if (bounce == 0) path_add(frame.background.rgb);
    return false;
  }
  WalkObjectGPU o = walk_objects[hit.object];
  vec3 n = hit.normal, ng = hit.geometric_normal;
  if (o.sigma_s.w < 0.5f) {
    if (dot(n, path_direction) > 0.0f) n = -n, ng = -ng;
    path_add(lambertian_next_event(hit, n, o.albedo.rgb));
    path_direction = sample_cosine(n, rnd(), rnd());
    path_origin = hit.position + hit.offset * ng;
    path_throughput *= o.albedo.rgb;
    return roulette();
  }
  if (dot(ng, path_direction) > 0.0f) return false;  // an inside face seen from outside: a leaky mesh
  float eta = o.sigma_a.w;
  float F = fresnel_reflectance(eta, abs(dot(path_direction, n)));
  if (rnd() < F) {
    path_direction = mirror_direction(path_direction, n);
    path_origin = hit.position + hit.offset * ng;
  } else {
    path_direction = refract_direction(path_direction, n, eta);
    path_throughput /= eta * eta;
    path_origin = hit.position - hit.offset * ng;
    path_medium = hit.object;
  }
  return true;
}

// ---- paths in flight ----------------------------------------------------------------------------------------
layout(std430, binding = LUCENT_BINDING_WALK_PATHS) buffer PathBlock { WalkPathGPU paths[]; };
layout(std430, binding = LUCENT_BINDING_WALK_COUNTERS) buffer WalkCounterBlock { WalkCountersGPU walk_counters; };

layout(std430, binding = LUCENT_BINDING_WALK_RESULTS) writeonly buffer ResultBlock { vec4 results[]; };

int path_bounce;
uint path_index;  // in its region's frame (LUCENT_WALK_NO_PATH: none)
uint path_flags;  // LUCENT_WALK_RESULT_* of its camera ray

// Path `index` of region `region`: sample index / pixels from the region's first, pixel index % pixels (row 0 the
// top one, as the references' images), from the camera through the pixel's centre.
void start_path(uint index, uint region) {
  uint pixels = method.pool.w, pixel_index = index % pixels;
  uint sample_index = method.region_first[region / 4u][region % 4u] + index / pixels;
  ivec2 size = frame.output_size.xy;
  ivec2 pixel = ivec2(int(pixel_index) % size.x, size.y - 1 - int(pixel_index) / size.x);
  float sx = (2.0f * (float(pixel.x) + 0.5f) / float(size.x) - 1.0f) * method.forward.w * method.right.w;
  float sy = (2.0f * (float(pixel.y) + 0.5f) / float(size.y) - 1.0f) * method.forward.w;
  rng_key = seed_from(method.samples.z, pixel_index, sample_index, 0x5157a1u ^ frame.seeds.w);  // every bit of the seed
  rng_count = 0u;
  path_origin = method.eye.xyz;
  path_direction = normalize(method.forward.xyz + sx * method.right.xyz + sy * method.up.xyz);
  path_throughput = vec3(1.0f), path_r_u = vec3(1.0f), path_radiance = vec3(0.0f);
  path_hero = min(2, int(rnd() * 3.0f));
  path_medium = -1, path_events = 0, path_scatterings = 0, path_bounce = 0;
  path_steps = 0u;
  path_jump_start = pcg_hash(rng_key ^ 0x6a09e667u), path_jumps = 0u;
  path_index = index, path_region = region, path_flags = 0u;
}

// The path's state as stored between dispatches (and kept before each event, to replay one the loop cap cut).
WalkPathGPU packed_path() {
  WalkPathGPU p;
  p.origin = vec4(path_origin, float(path_bounce));
  p.direction = vec4(path_direction, 0.0f);
  p.throughput = vec4(path_throughput, 0.0f);
  p.r_u = vec4(path_r_u, 0.0f);
  p.radiance = vec4(path_radiance, 0.0f);
  p.info = ivec4(path_hero, path_medium, path_events, path_scatterings);
  p.state = uvec4(rng_key, rng_count, path_steps,
                  path_index == LUCENT_WALK_NO_PATH ? path_index : path_index | (path_region << LUCENT_WALK_REGION_SHIFT));
  p.jumps = uvec4(path_jump_start, path_jumps, path_flags, 0u);
  return p;
}

void unpack_path(WalkPathGPU p) {
  path_origin = p.origin.xyz, path_bounce = int(p.origin.w);
  path_direction = p.direction.xyz, path_throughput = p.throughput.xyz, path_r_u = p.r_u.xyz;
  path_radiance = p.radiance.xyz;
  path_hero = p.info.x, path_medium = p.info.y, path_events = p.info.z, path_scatterings = p.info.w;
  rng_key = p.state.x, rng_count = p.state.y, path_steps = p.state.z;
  bool none = p.state.w == LUCENT_WALK_NO_PATH;
  path_index = none ? p.state.w : p.state.w & ((1u << LUCENT_WALK_REGION_SHIFT) - 1u);
  path_region = none ? 0u : p.state.w >> LUCENT_WALK_REGION_SHIFT;
  path_jump_start = p.jumps.x, path_jumps = p.jumps.y, path_flags = p.jumps.z;
}

// One event of the path: a medium step or a surface interaction. False when the path ended.
bool path_event() {
  if (path_events >= method.limits.w) return false;  // never reached by a physical path (see the method's doc)
  if (path_medium >= 0) return medium_step();
  if (path_bounce >= method.limits.x) return false;
  Hit hit = trace_from_surface(path_origin, path_direction, 1e30f);
  if (path_bounce == 0 && hit.object >= 0)
    path_flags = LUCENT_WALK_RESULT_COVERED | (translucent(hit.object) ? LUCENT_WALK_RESULT_TRANSLUCENT : 0u);
  return surface_step(path_bounce++, hit);
}

// Adds v to the 64-bit counter (low, high) of walk_counters named by `which`.
void add_count(uint which, uint v) {
  if (v == 0u) return;
  uint low = 0u;
  if (which == 0u) low = atomicAdd(walk_counters.steps.x, v);
  else if (which == 1u) low = atomicAdd(walk_counters.traversals.x, v);
  else if (which == 2u) low = atomicAdd(walk_counters.node_visits.x, v);
  else if (which == 3u) low = atomicAdd(walk_counters.next_events.x, v);
  else low = atomicAdd(walk_counters.next_event_traversals.x, v);
  if (low + v >= low) return;  // no carry
  if (which == 0u) atomicAdd(walk_counters.steps.y, 1u);
  else if (which == 1u) atomicAdd(walk_counters.traversals.y, 1u);
  else if (which == 2u) atomicAdd(walk_counters.node_visits.y, 1u);
  else if (which == 3u) atomicAdd(walk_counters.next_events.y, 1u);
  else atomicAdd(walk_counters.next_event_traversals.y, 1u);
}

// A path index from region r's counter, or region_paths once its paths have all started.
uint take_path(uint r, uint region_paths) {
  return walk_counters.next_path[r] < region_paths ? atomicAdd(walk_counters.next_path[r], 1u) : region_paths;
}

// One slot of the pool: its path advances event by event while the invocation's loop iterations stay under the
// budget; when it ends, its result goes to the batch's results and the slot takes the batch's next path.
void main() {
  uint slot = gl_GlobalInvocationID.x;
  if (slot >= method.pool.x) return;
  uint region_paths = method.pool.y, current = method.pool.z, regions = method.ring.x;
  if (method.dispatch.x != 0u) path_index = LUCENT_WALK_NO_PATH;
  else unpack_path(paths[slot]);
  uint steps_done = 0u, finished = 0u;
  // loop bound: checked; events end once loop_count reaches method.dispatch.y, which random_walk.cpp budgets well under kLlvmpipeLoopIterations
  for (int event = 0; event < 1000000 && loop_count < method.dispatch.y; ++event) {
    ++loop_count;
    if (path_index == LUCENT_WALK_NO_PATH) {  // the current frame's next path, else the next frames' in turn
      // Without a loop: where llvmpipe's loop cap ends a loop, it leaves at the loop's end, an exit the compiler
      // does not know of, so a condition the compiler computed once for the loop's exit and the code after it is
      // stale there. A loop here took a path index from the counter and then, testing that stale condition,
      // dropped it: the frame waited for a path no slot held (docs/methods/random-walk.md, "Paths in flight").
      uint region = current, index = take_path(current, region_paths);
      if (index >= region_paths && regions > 1u) region = (current + 1u) % regions, index = take_path(region, region_paths);
      if (index >= region_paths && regions > 2u) region = (current + 2u) % regions, index = take_path(region, region_paths);
      if (index >= region_paths && regions > 3u) region = (current + 3u) % regions, index = take_path(region, region_paths);
#if LUCENT_WALK_MAX_FRAMES_IN_FLIGHT > 4
#error "the search above tries four frames"
#endif
      if (index >= region_paths) break;
      start_path(index, region);
    }
    // The driver's counter runs over the SIMD group (8 or 16 invocations), so a budget on this invocation's own
    // count cannot rule the cap out. An event the cap cut is undone and replayed, with the same random numbers, at
    // the start of the next dispatch: the path is the one it would have been. Only an event that the cap cuts even
    // as a dispatch's first is dropped (counted as loop_limited).
    WalkPathGPU before = packed_path();
    bool alive = path_event();
    bool limited = false;
    if (method.dispatch.z != 0u && loops_were_cut()) {
      if (event > 0) {
        unpack_path(before);
        atomicAdd(walk_counters.replayed, 1u);
        break;
      }
      limited = true;
    }
    if (alive && !limited) continue;
    // A path past the loop cap is dropped and counted (the loop_limited_paths statistic); a non-finite one (never
    // expected) counts as black.
    bool finite = all(greaterThanEqual(path_radiance, vec3(0.0f))) && all(lessThan(path_radiance, vec3(1e30f)));
    if (limited) atomicAdd(walk_counters.loop_limited, 1u);
    uint bits = path_flags | (limited ? 0u : LUCENT_WALK_RESULT_VALID);
    bits |= min(path_steps, (1u << 21u) - 1u) << 3u;
    results[path_region * region_paths + path_index] = vec4(finite && !limited ? path_radiance : vec3(0.0f), float(bits));
    atomicAdd(walk_counters.finished[path_region], 1u);
    steps_done += path_steps, ++finished;
    path_index = LUCENT_WALK_NO_PATH;
    if (limited) break;  // the cap ended every loop of this invocation: the next path starts in the next dispatch
  }
  paths[slot] = packed_path();
  if (path_index != LUCENT_WALK_NO_PATH) atomicAdd(walk_counters.busy, 1u);
  if (finished > 0u) atomicAdd(walk_counters.paths, finished);
  add_count(0u, steps_done);
  add_count(1u, stat_traversals);
  add_count(2u, stat_node_visits);
  add_count(3u, stat_next_events);
  add_count(4u, stat_next_event_traversals);
}
