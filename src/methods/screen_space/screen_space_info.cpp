// screen_space_info.cpp: the screen-space method as data: parameters, passes, statistics (no GL).
#include "methods/method_info.h"

namespace lucent::methods {
namespace {

constexpr ParamDecl kParams[] = {
    {"taps", ParamType::Int, "17", "taps", 7, 25, "", "taps of each 1D blur pass (denser near the profile's centre)", kLive},
    {"profile", ParamType::Enum, "\"burley\"", "", 0, 0, "burley|gaussians",
     "diffusion profile: Burley's normalized diffusion, or 6 Gaussians fitted to it", kLive},
    {"transmittance", ParamType::Bool, "true", "", 0, 1, "",
     "add the light crossing thin parts from behind (thickness from the light G-buffer, the profile's transmittance)",
     kLive},
    {"depth_threshold", ParamType::Float, "1", "kernel radii", 0.01, 100, "",
     "a tap whose depth differs from the centre's by this many kernel radii counts as the centre (blended linearly)", kLive},
    {"light_map_size", ParamType::Int, "512", "texels", 8, 8192, "", "resolution of each light G-buffer layer (shadows, thickness)"},
    {"visibility_taps", ParamType::Int, "3", "taps/axis", 1, 7, "", "multi-sampled shadow taps per axis", kLive},
    {"specular", ParamType::Bool, "true", "", 0, 1, "", "add GGX specular reflection of the lights", kLive},
    {"roughness", ParamType::Float, "0.15", "GGX alpha", 0.01, 1, "", "roughness of the specular reflection", kLive},
};

constexpr PassDecl kPasses[] = {
    {"light_gbuffer", "one layered G-buffer of every light (shadow maps; entry points for the transmittance)"},
    {"irradiance", "the irradiance transmitted into each translucent camera pixel"},
    {"blur_horizontal", "1D profile blur along x, width scaled by depth, depth-aware"},
    {"blur_vertical", "the same along y"},
    {"shade", "L = F_t(w_o) albedo (E_blurred + E_back) / pi, E_back the light crossing thin parts from behind; plus "
              "the shared specular terms"},
};

constexpr StatDecl kStats[] = {
    {"blur_taps", "", "kernel taps read this frame by the two blur passes"},
    {"blur_ms", "ms", "GPU time of the two blur passes"},
};

}  // namespace

extern const MethodInfo screen_space_info;
const MethodInfo screen_space_info{
    .name = "screen-space",
    .summary = "separable screen-space blur of the irradiance with a Burley normalized-diffusion kernel (Jimenez et al. 2015), "
               "transmittance through thin parts (Jimenez et al. 2010)",
    .params = kParams,
    .passes = kPasses,
    .stats = kStats,
    .quick_settings = R"({"light_map_size": 128, "specular": false})",
    // Measured 41.7% brighter than the standard dipole's bssrdf reference on llvmpipe (0.0609 against 0.0430; 13%
    // above volpath's 0.0537): the blur is normalised to the flat total, which the 1 mm sphere (about as wide as
    // the profile) does not reach.
    .reference_tolerance = 0.53,
    // Where methods are weakest, against the bssrdf reference (llvmpipe, 2026-11-28, measured values after each):
    .weakest = ConformanceTolerances{0.77,   // sphere, per pixel: 0.603
                                     0.20, 0.23,  // backlit thin slab, mean and per pixel: 0.148, 0.173
                                     0.71, 0.87},  // coarse box: 0.557, 0.686
};

}  // namespace lucent::methods
