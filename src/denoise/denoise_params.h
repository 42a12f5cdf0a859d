// denoise_params.h: the parameters of the denoising stage that runs after any method's passes (the scene's
// "denoise" object, `lucent render --denoise`, Python's scene dictionary, the viewer's D key). Off by default and
// for every reference: what it returns is a biased estimate of the method's image, traded for less noise.
//
// The stage (denoise/denoiser.h) keeps the method's estimate across camera moves by reprojecting it, and filters it
// with an edge-stopping a-trous wavelet (Dammertz et al. 2010; guided by variance as in SVGF, Schied et al. 2017)
// on the radiance divided by each surface's albedo. Every parameter is read each frame (live).
#pragma once
#include "lucent/params.h"

namespace lucent::denoise {

inline constexpr ParamDecl kDenoiseParams[] = {
    {"enabled", ParamType::Bool, "false", "", 0, 1, "",
     "filter the method's image: reprojected history across camera moves and an edge-stopping wavelet filter "
     "(biased; references never use it)", kLive},
    {"iterations", ParamType::Int, "5", "passes", 0, 8, "",
     "a-trous wavelet passes; pass k reaches 2^(k+1) pixels (0: temporal reuse only)", kLive},
    {"sigma_luminance", ParamType::Float, "8", "std devs", 0.01, 1000, "",
     "luminance edge-stopping: differences of this many estimated standard deviations weigh e^-1", kLive},
    {"normal_power", ParamType::Float, "4", "", 1, 4096, "",
     "normal edge-stopping: a neighbour weighs max(0, n.n')^power", kLive},
    {"sigma_plane", ParamType::Float, "2", "pixels", 0.01, 1000, "",
     "depth edge-stopping: a neighbour this many pixel footprints off the pixel's tangent plane, per pixel of "
     "offset, weighs e^-1", kLive},
    {"history_frames", ParamType::Int, "32", "frames", 0, 65536, "",
     "frames of reprojected history kept at most across a camera move (0: start again at each move)", kLive},
    {"fade_frames", ParamType::Float, "128", "frames", 0, 1e9, "",
     "the filtered image weighs fade^2 / (fade^2 + frames^2) against the unfiltered average, so that a still view "
     "converges to the method's unbiased average (0: no fade)", kLive},
};

// The stage's settings as the renderer uses them.
struct DenoiseSettings {
  bool enabled = false;
  int iterations = 5;
  float sigma_luminance = 8.0f;
  float normal_power = 4.0f;
  float sigma_plane = 2.0f;
  int history_frames = 32;
  float fade_frames = 128.0f;
};

// From the scene's "denoise" values (declared above); defaults for what `values` lacks.
DenoiseSettings denoise_settings(const ParamValues& values);

}  // namespace lucent::denoise
