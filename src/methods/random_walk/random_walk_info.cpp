// random_walk_info.cpp: the random-walk method as data: parameters, passes, statistics (no GL).
#include "methods/method_info.h"
#include "methods/random_walk/random_walk_io.h"

namespace lucent::methods {
namespace {

constexpr ParamDecl kParams[] = {
    {"samples_per_frame", ParamType::Int, "1", "paths/pixel", 1, 1024, "", "paths traced per pixel each frame", kLive},
    {"sphere_jumps", ParamType::Bool, "true", "", 0, 1, "",
     "deep inside homogeneous media, jump across spheres that lie wholly inside the medium (exact: sampled sphere "
     "exits) instead of stepping through every scattering event",
     kLive},
    {"sphere_walk_records", ParamType::Int, "256", "records", 64, 4096, "",
     "sphere-walk records generated per level each frame (rounded down to a power of two; from optical radius 32 on "
     "each level has half as many): more cost more per frame and correlate the pixels of a frame less"},
    {"max_scatter", ParamType::Int, "0", "events", 0, 1000000, "",
     "paths end after this many scattering events in media (0: no limit; 1: single scattering), as volpath's "
     "--max-scatter",
     kLive},
    {"distance_grid", ParamType::Int, "64", "cells/axis", 8, 256, "",
     "resolution of the distance field that bounds the sphere jumps (cells along the longest axis)"},
    {"max_dispatches", ParamType::Int, "65536", "dispatches", 1, 1 << 30, "",
     "a frame whose paths have not all left after this many trace dispatches is refused with an error (a path that "
     "never leaves a medium without absorption would otherwise keep the frame forever)"},
    {"frames_in_flight", ParamType::Int, "2", "frames", 1, LUCENT_WALK_MAX_FRAMES_IN_FLIGHT, "",
     "frames whose paths the pool traces at once: slots the current frame's paths no longer need start the next "
     "frames' (1: each frame alone)"},
    {"loop_budget", ParamType::Int, "0", "iterations", 0, 1 << 20, "",
     "loop iterations per invocation under which a trace dispatch starts another event (0: automatic, a quarter "
     "of llvmpipe's loop cap there, 65,536 elsewhere); past llvmpipe's cap an event is undone and replayed in the "
     "next dispatch, so a larger budget means fewer dispatches and more replays"},
    {"time_dispatches", ParamType::Bool, "false", "", 0, 1, "",
     "measurement: wait for each trace dispatch and time it by wall clock, reading the counters after each (slower: "
     "a read-back per dispatch), to report the share of the trace time spent in sparse dispatches"},
};

constexpr PassDecl kPasses[] = {
    {"sphere_walks", "the frame's sphere-jump records: walks from a sphere's centre to its surface, per level"},
    {"refit", "animated scenes: the deformed triangles gathered and the hierarchy's boxes refitted (CPU), uploaded"},
    {"trace", "volumetric path tracing of every pixel through the bounding volume hierarchy"},
};

constexpr StatDecl kStats[] = {
    {"steps_per_path", "", "mean walk steps per path of the frame's pixels that hit something (free flights, "
     "tentative collisions of delta tracking and sphere jumps in media, as volpath counts them)"},
    {"walk_steps", "", "the walk steps of the frame's paths"},
    {"walk_paths", "", "the frame's paths of pixels that hit something (volpath counts those)"},
    {"paths_per_second", "1/s", "paths finished per second of the trace pass (of this frame and the next ones in flight)"},
    {"steps_per_second", "1/s", "their walk steps per second of the trace pass"},
    {"traversals_per_step", "", "rays traced through the bounding volume hierarchy per walk step"},
    {"traversals_per_next_event", "", "of them, those of next-event estimates, per estimate at a medium vertex"},
    {"node_visits_per_step", "", "hierarchy nodes visited per walk step"},
    {"dispatches", "", "trace dispatches with work this frame"},
    {"sparse_dispatches", "", "of them, those with under a tenth of the pool's slots busy (the tail of long paths)"},
    {"sparse_time_share", "", "the share of the measured dispatch time spent in sparse dispatches (with time_dispatches on; 0 otherwise)"},
    {"read_backs", "", "blocking reads of the walk's counters this frame (one per round of indirect dispatches)"},
    {"loop_limited_paths", "", "paths dropped this frame: an event the driver's loop cap (llvmpipe) cut at a dispatch's start"},
    {"replayed_events", "", "events the driver's loop cap cut, undone and replayed in the next dispatch (llvmpipe)"},
};

}  // namespace

extern const MethodInfo random_walk_info;
const MethodInfo random_walk_info{
    .name = "random-walk",
    .summary = "the physics on the GPU: volumetric path tracing with sphere jumps, converging to the volpath reference",
    .params = kParams,
    .passes = kPasses,
    .stats = kStats,
    .quick_settings = R"({"samples_per_frame": 4})",
    // Against the bssrdf reference (the diffusion model), not the physics it estimates: the conformance sphere is
    // two transport mean free paths in radius, where the half-space model misses the light leaving through the
    // back and the light its curved boundary focuses: measured 60% brighter than the standard dipole on llvmpipe
    // (0.0692 against 0.0431; 25% before volpath counted every refracted path with its focusing), and equal to
    // volpath within noise (below and tests/gl/test_random_walk.cpp).
    .reference_tolerance = 0.75,
    .estimates_volpath = true,     // estimates_volpath
    // Where methods are weakest, against the volpath reference (llvmpipe, 2026-11-29, measured values after each):
    .weakest = ConformanceTolerances{0.28,   // sphere, per pixel: 0.208
                                     0.02, 0.32,  // backlit thin slab, mean and per pixel: 0.001, 0.232
                                     0.02, 0.26},  // coarse box: 0.001, 0.183
};

}  // namespace lucent::methods
