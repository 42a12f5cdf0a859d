// per_pixel_info.cpp: the per-pixel method as data: parameters, passes, statistics (no GL).
#include "methods/method_info.h"

namespace lucent::methods {
namespace {

constexpr ParamDecl kParams[] = {
    {"N", ParamType::Int, "32", "samples", 1, 65536, "", "samples per colour band per pixel per frame", kLive},
    {"light_map_size", ParamType::Int, "512", "texels", 8, 8192, "", "resolution of each light G-buffer layer"},
    {"visibility_taps", ParamType::Int, "3", "taps/axis", 1, 7, "", "multi-sampled shadow taps per axis", kLive},
    {"progressive", ParamType::Bool, "true", "", 0, 1, "", "accumulate while nothing (camera included) changes", kLive},
    {"specular", ParamType::Bool, "true", "", 0, 1, "", "add GGX specular reflection of the lights", kLive},
    {"roughness", ParamType::Float, "0.15", "GGX alpha", 0.01, 1, "", "roughness of the specular reflection", kLive},
};

constexpr PassDecl kPasses[] = {
    {"light_gbuffer", "one layered G-buffer of every light"},
    {"per_pixel", "N light-space samples of eq. 9 per camera pixel, accumulated while nothing moves"},
};

constexpr StatDecl kStats[] = {
    {"bssrdf_samples", "", "light-space samples drawn this frame (each evaluates S_d once if lit)"},
    {"bssrdf_samples_per_second", "1/s", "bssrdf_samples over the per_pixel pass's GPU time"},
};

}  // namespace

extern const MethodInfo per_pixel_info;
const MethodInfo per_pixel_info{
    .name = "per-pixel",
    .summary = "caching-free baseline: the same light-space sampling per screen pixel every frame (Dal Corso et al. Fig. 11)",
    .params = kParams,
    .passes = kPasses,
    .stats = kStats,
    .quick_settings = R"({"N": 16, "light_map_size": 128, "specular": false})",
    // Measured 1.4% on llvmpipe
    .reference_tolerance = 0.05,
    .reads_material_maps = true,  // textured materials: eq. 9 with the coefficients at the pixel's texture coordinates
    // Where methods are weakest, against the bssrdf reference (llvmpipe, 2026-11-28, measured values after each):
    .weakest = ConformanceTolerances{0.18,   // sphere, per pixel: 0.133
                                     0.02, 0.10,  // backlit thin slab, mean and per pixel: 0.001, 0.069
                                     0.02, 0.16},  // coarse box: 0.002, 0.116
};

}  // namespace lucent::methods
