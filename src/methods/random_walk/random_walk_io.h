// random_walk_io.h: the random-walk method's GPU data (C++ and GLSL): its uniform block (at LUCENT_BINDING_METHOD),
// the scene's bounding volume hierarchy and triangles, each object's medium, and its binding points inside the
// method ranges of shared/bindings.h.
#ifndef LUCENT_METHODS_RANDOM_WALK_IO_H
#define LUCENT_METHODS_RANDOM_WALK_IO_H
#include "shared/shader_io.h"

#define LUCENT_BINDING_WALK_NODES 20      // BvhNodeGPU[] (std430)
#define LUCENT_BINDING_WALK_TRIANGLES 21  // TriangleGPU[] (std430)
#define LUCENT_BINDING_WALK_OBJECTS 22    // WalkObjectGPU[] per scene object (std430)
#define LUCENT_BINDING_WALK_SPHERES 23    // SphereWalkGPU[]: the frame's sphere-jump records (std430)
#define LUCENT_BINDING_WALK_PATHS 24      // WalkPathGPU[]: the pool of paths in flight (std430)
#define LUCENT_BINDING_WALK_COUNTERS 25   // WalkCountersGPU (std430)
#define LUCENT_BINDING_WALK_NEIGHBOURS 26 // ivec4[] per TriangleGPU: xyz its neighbours across edges 0-1, 1-2, 2-0 (-1: none)
#define LUCENT_BINDING_WALK_AREAS 27      // vec2[] per translucent object's triangles: x the cumulative area fraction,
                                          // y the triangle's index (float bits); WalkObjectGPU.mesh_lower/upper.w
#define LUCENT_BINDING_WALK_FACES 28      // vec4[]: the translucent objects' large flat faces (geometry/flat_patches.h),
                                          // xyz the unit normal; WalkObjectGPU.faces; a triangle's face: its
                                          // neighbours entry's w
#define LUCENT_BINDING_WALK_RESULTS 29    // vec4[] per path of the batch: rgb its radiance, a its LUCENT_WALK_RESULT_* bits
#define LUCENT_IMAGE_WALK_SUM 2           // RGBA32F: rgb the sum of the path samples, a their count
#define LUCENT_TEX_WALK_DISTANCE 8        // R32F 3D: distance from each cell centre to the nearest surface

// WalkObjectGPU.g.w: the medium's heterogeneous field (kField* of media/heterogeneous_field.h).
// RandomWalkGPU.flags bits.
#define LUCENT_WALK_SPHERE_JUMPS 1
#define LUCENT_WALK_MAX_JUMP_BANKS 4
#define LUCENT_WALK_NO_PATH 0xffffffffu  // WalkPathGPU.state.w of a free slot
#define LUCENT_WALK_REGION_SHIFT 26u  // WalkPathGPU.state.w: the path's results region in the top 6 bits
#define LUCENT_WALK_MAX_REGIONS 64    // results regions the layout holds
#define LUCENT_WALK_MAX_FRAMES_IN_FLIGHT 4  // regions the ring uses at most: the trace pass tries each in turn
#define LUCENT_WALK_POOL_FIRST 1    // RandomWalkGPU.ring.y: the frame's first batch
#define LUCENT_WALK_POOL_LAST 2     // its last
#define LUCENT_WALK_POOL_GROUP 64        // invocations per work group of the trace pass (one slot each)
// A path's result bits (WalkPathGPU.jumps.z; the results' a holds them | its walk steps << 3, exact in a float up
// to 2^21 steps).
#define LUCENT_WALK_RESULT_VALID 1        // counted in the average (not dropped at the loop cap)
#define LUCENT_WALK_RESULT_COVERED 2      // its camera ray hit an object
#define LUCENT_WALK_RESULT_TRANSLUCENT 4  // a translucent one  // distinct Henyey-Greenstein g values with sphere jumps
LUCENT_SHADER_BEGIN

// One node of the flattened BVH (methods/random_walk/triangle_bvh.h), depth-first: an interior node's left child
// is the next node (index + 1). The integer fields are stored as float bits (intBitsToFloat / floatBitsToInt in
// GLSL, std::bit_cast in C++).
struct BvhNodeGPU {
  vec4 lower;  // xyz: box minimum [scene units]; w: leaf: index of its first triangle; interior: right child's index
  vec4 upper;  // xyz: box maximum [scene units]; w: triangle count (0: interior node)
};

// One world-space triangle, in the BVH's leaf order.
struct TriangleGPU {
  vec4 p0;  // xyz: corner 0 [scene units]; w: the scene object's index (float bits)
  vec4 e1;  // xyz: corner 1 - corner 0; w: 0
  vec4 e2;  // xyz: corner 2 - corner 0; w: 0
  vec4 n0;  // xyz: unit shading normal at corner 0; w: the triangle's index before the BVH reordered them
            // (float bits)
  vec4 n1;  // xyz: unit shading normal at corner 1; w: 0
  vec4 n2;  // xyz: unit shading normal at corner 2; w: 0
};

// One scene object as the walk sees it (std430, 160 bytes): a medium behind a dielectric boundary, or a
// Lambertian surface. Coefficients in 1/scene unit, unreduced sigma_s.
struct WalkObjectGPU {
  vec4 sigma_a;   // xyz; w: eta (relative index)
  vec4 sigma_s;   // xyz; w: 1 translucent, 0 opaque
  vec4 g;         // xyz: Henyey-Greenstein g per band; w: the field (kField*)
  vec4 albedo;    // rgb: an opaque object's diffuse albedo
  vec4 lower;     // xyz: the field's world box [scene units]; w: the field's feature size [scene units]
  vec4 upper;     // xyz; w: the field's contrast
  vec4 majorant;  // xyz: max m sigma_t per band; w: the sphere-jump bank of its g (-1: no jumps; g differs by band)
  vec4 mesh_lower;  // xyz: the mesh's own world box (a vertex outside it has leaked out of a closed mesh); w: its
                    // triangles' first entry in the area distribution (LUCENT_BINDING_WALK_AREAS; float bits)
  vec4 mesh_upper;  // xyz; w: their count (float bits)
  ivec4 faces;      // x: its first large flat face (LUCENT_BINDING_WALK_FACES), y: their count; zw: unused
};

// One slot of the pool of paths in flight (std430, 128 bytes): a path advances over as many dispatches as it
// needs, each invocation running events only while its loop iterations stay under the budget; a slot whose path
// ended takes the frame's next path.
struct WalkPathGPU {
  vec4 origin;      // xyz [scene units]; w: the surface bounces so far
  vec4 direction;   // xyz: unit
  vec4 throughput;  // xyz: per band, divided by the hero band's path pdf
  vec4 r_u;         // xyz: each band's path pdf over the hero's
  vec4 radiance;    // xyz: what the path gathered so far
  ivec4 info;       // x: hero band, y: medium (object index, -1 outside), z: events, w: scattering events
  uvec4 state;      // x: random stream key, y: random numbers drawn, z: walk steps, w: the path's index in the
                    // region | its region << LUCENT_WALK_REGION_SHIFT (LUCENT_WALK_NO_PATH: the slot is free)
  uvec4 jumps;      // x: the path's first sphere-walk record (an offset, modulo a level's records); y: jumps made;
                    // z: LUCENT_WALK_RESULT_* bits of its camera ray; w: unused
};

// The pool's progress through the frames in flight (the current one in its results region, the next ones in the
// ring's other regions) and what the dispatches of a frame count (std430). The 64-bit sums are (low, high) words;
// from `busy` on, zeroed each frame.
struct WalkCountersGPU {
  uint next_path[LUCENT_WALK_MAX_REGIONS];  // per region: its next path index to start (a free slot takes one)
  uint finished[LUCENT_WALK_MAX_REGIONS];   // per region: its paths finished
  uint busy;               // slots holding a path after the dispatch (the control pass reads and zeroes it)
  uint loop_limited;       // paths dropped: an event the driver's loop cap cut as a dispatch's first
  uint replayed;           // events the driver's loop cap cut, undone and replayed in the next dispatch
  uint paths;              // paths finished
  uint dispatches;         // trace dispatches with work after the frame's first
  uint sparse_dispatches;  // of them, those with under a tenth of the slots busy
  uint last_busy;          // `busy` as the last control pass found it (diagnostics: a path in flight or none)
  uint lost;               // the current frame's paths neither finished nor held by a slot when none is left to
                           // start (never expected: the frame stops, and the host reports it)
  uvec4 groups;            // xyz: the next trace dispatch's work groups (read by glDispatchComputeIndirect); w: 0
  uvec4 resolve_groups;    // xyz: the resolve pass's work groups once the current frame's paths have all finished
  uvec2 steps;             // walk steps of the finished paths
  uvec2 traversals;        // rays traced through the hierarchy
  uvec2 node_visits;       // hierarchy nodes they visited
  uvec2 next_events;       // next-event estimates at medium vertices
  uvec2 next_event_traversals;  // the rays they traced
  uvec2 frame_steps;       // the resolved frame's paths: their walk steps, and (next) their count
  uint frame_paths, pad2, pad3, pad4;
};

struct RandomWalkGPU {
  vec4 eye;              // xyz: camera position [scene units]
  vec4 forward;          // xyz: unit view direction; w: tan(fov_y / 2)
  vec4 right;            // xyz: unit right; w: aspect ratio
  vec4 up;               // xyz: unit up
  uvec4 samples;         // x: samples per pixel this frame, y: index of the first, z: user seed, w: flags (LUCENT_WALK_*)
  ivec4 limits;          // x: surface bounces, y: events before Russian roulette, z: scattering events (0: no limit),
                         // w: events per path
  uvec4 pool;            // x: slots in the pool of paths in flight; y: paths per region (samples x the image's
                         // pixels); z: the current frame's region; w: the image's pixels
  uvec4 ring;            // x: regions in the ring (1: the frame alone; k > 1: the next k - 1 frames' paths start in
                         // the following regions once the current one's are all under way); y: LUCENT_WALK_POOL_*
                         // bits; z, w: the sphere-walk banks to generate: of w regions from region z on
  uvec4 region_first[LUCENT_WALK_MAX_REGIONS / 4];  // the first sample index of each region's paths
  uvec4 dispatch;        // x: 1 in the batch's first dispatch (every slot free); y: loop iterations under which an
                         // invocation starts another event; z: the driver's loop cap per invocation (0: none); w: 2,
                         // the iterations of the loop that detects the cap
  vec4 distance_lower;   // xyz: the distance grid's first cell corner [scene units]; w: its cell size
  ivec4 distance_size;   // xyz: cells per axis; w: the sphere-walk records of one bank and level (the stride)
  vec4 jump_g;           // the Henyey-Greenstein g of sphere-jump banks 0..3
  vec4 jump_bound;       // x: how far any surface point has moved since the distance grid was built [scene units];
                         // y: 1 when the distance grid is bound; zw: unused
  ivec4 jump_records[2]; // records of each level (kSphereJumpLevelCount used)
  ivec4 jump_info;       // x: sphere-jump banks; yzw: unused
  ivec4 light_media[LUCENT_MAX_LIGHTS / 4];  // per FrameGPU light: the object whose medium encloses it, or -1
};

LUCENT_SHADER_END

#if defined(__cplusplus)
#include <cstddef>
static_assert(sizeof(lucent::shader::BvhNodeGPU) == 32);
static_assert(offsetof(lucent::shader::BvhNodeGPU, upper) == 16);
static_assert(sizeof(lucent::shader::TriangleGPU) == 96);
static_assert(offsetof(lucent::shader::TriangleGPU, n0) == 48);
static_assert(offsetof(lucent::shader::TriangleGPU, n2) == 80);
static_assert(sizeof(lucent::shader::WalkObjectGPU) == 160);
static_assert(sizeof(lucent::shader::RandomWalkGPU) == 512 + 4 * LUCENT_MAX_LIGHTS);
static_assert(sizeof(lucent::shader::WalkPathGPU) == 128);
static_assert(sizeof(lucent::shader::WalkCountersGPU) == 640);
static_assert(LUCENT_WALK_MAX_FRAMES_IN_FLIGHT <= LUCENT_WALK_MAX_REGIONS);
static_assert(offsetof(lucent::shader::WalkCountersGPU, groups) == 544);
static_assert(offsetof(lucent::shader::WalkCountersGPU, busy) == 512);
static_assert(LUCENT_BINDING_WALK_NODES >= LUCENT_METHOD_STORAGE_FIRST && LUCENT_BINDING_WALK_RESULTS <= LUCENT_METHOD_STORAGE_LAST);
static_assert(LUCENT_IMAGE_WALK_SUM >= LUCENT_METHOD_IMAGE_FIRST && LUCENT_IMAGE_WALK_SUM <= LUCENT_METHOD_IMAGE_LAST);
static_assert(LUCENT_TEX_WALK_DISTANCE >= LUCENT_METHOD_TEX_FIRST && LUCENT_TEX_WALK_DISTANCE <= LUCENT_METHOD_TEX_LAST);
#endif

#endif
