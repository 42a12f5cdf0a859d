// radiosity_maps_info.cpp: the radiosity-maps method as data: parameters, passes, statistics (no GL).
#include "methods/method_info.h"
#include "methods/radiosity_maps/radiosity_maps_io.h"

namespace lucent::methods {
namespace {

// Defaults follow Dal Corso et al. 2015, Section 5 (512x512 maps and light map, K = 16) and lucent's
// benchmark configuration (N = 32 per band). Live parameters are read every frame; the others size buffers.
constexpr ParamDecl kParams[] = {
    {"K", ParamType::Int, "16", "maps", 1, LUCENT_MAX_MAPS, "", "number of scattered-radiosity maps (views)"},
    {"directions", ParamType::Enum, "\"halton\"", "", 0, 0, "halton|fibonacci",
     "automatic map directions: Halton points (the paper) or a spherical Fibonacci set (more even)"},
    {"map_directions", ParamType::Vec3List, "[]", "", -1e9, 1e9, "",
     "user map directions (from the object toward each map camera); non-empty: overrides K and directions"},
    {"N", ParamType::Int, "32", "samples", 1, 4096, "", "samples per colour band per map texel per frame", kLive},
    {"map_size", ParamType::Int, "512", "texels", 8, 4096, "", "resolution of each scattered-radiosity map"},
    {"light_map_size", ParamType::Int, "512", "texels", 8, 8192, "", "resolution of each light G-buffer layer"},
    {"eps_bias", ParamType::Float, "2.0", "map texels", 0, 64, "", "visibility depth bias of Algorithm 1", kLive},
    {"eps_comb", ParamType::Float, "1.0", "map texels", 0, 64, "", "offset of x_o along -n_o (Algorithm 1)", kLive},
    {"visibility_taps", ParamType::Int, "3", "taps/axis", 1, 7, "", "multi-sampled visibility: taps per axis", kLive},
    {"filter_lod", ParamType::Float, "0.0", "mip level", 0, 4, "",
     "mip level read from the maps (noise filter); the mipmaps are built only when it is above 0", kLive},
    {"progressive", ParamType::Bool, "true", "", 0, 1, "", "accumulate maps over frames while only the camera moves",
     kLive},
    {"converged_after", ParamType::Int, "0", "frames", 0, 1e9, "",
     "converged mode (Section 3.2): after this many accumulated frames with nothing but the camera changing, "
     "only the combine pass runs (0: never)",
     kLive},
    {"specular", ParamType::Bool, "true", "", 0, 1, "", "add GGX specular reflection of the lights", kLive},
    {"roughness", ParamType::Float, "0.15", "GGX alpha", 0.01, 1, "", "roughness of the specular reflection", kLive},
    {"vpls", ParamType::Int, "64", "VPLs", 0, 4096, "", "virtual point lights carrying emergent light to diffuse objects (0: off)"},
    {"vpl_map_size", ParamType::Int, "256", "texels", 8, 4096, "", "resolution of each face of the VPL placement cube map"},
    {"view", ParamType::Enum, "\"shaded\"", "", 0, 0, "shaded|coverage",
     "debug view: coverage shows unmapped areas in magenta", kLive},
};

constexpr PassDecl kPasses[] = {
    {"light_gbuffer", "step 1: one layered G-buffer of every light"},
    {"map_gbuffers", "step 2: the K map views' G-buffers (layered)"},
    {"integrate", "step 2: N light-space samples of eq. 9 per map texel, accumulated"},
    {"mipmaps", "step 2: the maps' mip chain (only when filter_lod > 0)"},
    {"vpls", "Section 3.4: VPLs placed on the outermost surface, their radiosity from the maps"},
    {"combine", "step 3: Algorithm 1 per camera pixel, L_o = F_t B / pi"},
};

constexpr StatDecl kStats[] = {
    {"bssrdf_samples", "", "light-space samples drawn this frame (each evaluates S_d once if lit)"},
    {"bssrdf_samples_per_second", "1/s", "bssrdf_samples over the integrate pass's GPU time"},
    {"covered_texels", "", "map texels that see a translucent surface"},
    {"maps", "", "number of maps K"},
    {"vpls", "", "virtual point lights N_vpl"},
    {"converged", "", "1 when the frame ran the combine pass only (converged mode)"},
};

}  // namespace

extern const MethodInfo radiosity_maps_info;
const MethodInfo radiosity_maps_info{
    .name = "radiosity-maps",
    .summary = "directional subsurface scattering cached in scattered-radiosity maps (Dal Corso et al. 2015)",
    .params = kParams,
    .passes = kPasses,
    .stats = kStats,
    .quick_settings = R"({"K": 8, "N": 16, "map_size": 64, "light_map_size": 128, "vpls": 0, "specular": false})",
    // Measured 1.2% on llvmpipe (the same model as the reference; what remains is map resolution and noise)
    .reference_tolerance = 0.05,
    .reads_material_maps = true,  // textured materials: eq. 9 per map texel with the coefficients at the texel's texture coordinates
    // Where methods are weakest, against the bssrdf reference (llvmpipe, 2026-11-28, measured values after each):
    .weakest = ConformanceTolerances{0.05,   // sphere, per pixel: 0.026
                                     0.02, 0.03,  // backlit thin slab, mean and per pixel: 0.003, 0.014
                                     0.02, 0.05},  // coarse box: 0.002, 0.031
};

}  // namespace lucent::methods
