// diffuse_wrap_info.cpp: the diffuse-wrap method as data: parameters, passes, statistics (no GL).
#include "methods/method_info.h"

namespace lucent::methods {
namespace {

constexpr ParamDecl kParams[] = {
    {"wrap", ParamType::Float, "0.2", "", 0, 1, "",
     "wrap lighting w: the cosine n.l becomes max(0, (n.l + w) / (1 + w)); 0 is Lambertian", kLive},
    {"light_map_size", ParamType::Int, "512", "texels", 8, 8192, "", "resolution of each light G-buffer layer (shadows)"},
    {"visibility_taps", ParamType::Int, "3", "taps/axis", 1, 7, "", "multi-sampled shadow taps per axis", kLive},
    {"specular", ParamType::Bool, "true", "", 0, 1, "", "add GGX specular reflection of the lights", kLive},
    {"roughness", ParamType::Float, "0.15", "GGX alpha", 0.01, 1, "", "roughness of the specular reflection", kLive},
};

constexpr PassDecl kPasses[] = {
    {"light_gbuffer", "one layered G-buffer of every light (shadow maps)"},
    {"shade", "Lambertian wrap lighting per camera pixel, albedo the material's total diffuse reflectance"},
};

}  // namespace

extern const MethodInfo diffuse_wrap_info;
const MethodInfo diffuse_wrap_info{
    "diffuse-wrap",
    "lower-bound baseline: Lambertian wrap lighting with the material's total diffuse reflectance, no transport",
    kParams,
    kPasses,
    {},
    R"({"light_map_size": 128, "specular": false})",
    // Measured 20.5% dark on llvmpipe (wrap 0.2): no light travels to the unlit side or through the sphere.
    0.25,
    false,
};

}  // namespace lucent::methods
