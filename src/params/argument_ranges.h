// argument_ranges.h: the ranges of the numbers that `lucent` subcommands and the Python module both take as
// arguments (lucent bssrdf and lucent.bssrdf, lucent reference and lucent.reference, ...), declared once so that
// both refuse the same values with the same words (number_range.h).
#pragma once
#include "params/number_range.h"

namespace lucent::argument_ranges {

// bssrdf: coefficients [mm^-1] (validate_material then asks what the model needs), g, eta, the entry and exit
// points [mm] and the normals and light direction (normalised after the check).
inline constexpr NumberRange kCoefficient{-1e6, 1e6, false, "mm^-1"};
inline constexpr NumberRange kAnisotropy{-1, 1, false, ""};
inline constexpr NumberRange kEta{1, 3, false, ""};
inline constexpr NumberRange kPointMm{-1e6, 1e6, false, "mm"};
inline constexpr NumberRange kDirection{-1e6, 1e6, false, ""};
inline constexpr NumberRange kIncidenceDeg{0, 89.9, false, "degrees"};

// reference: samples per pixel, threads (0: all cores), seed, scattering events (0: no limit), and the instant of
// an animated scene [s]: up to the last frame `lucent render --animate` reaches (render.frames 1e6 at render.fps 1e-3).
inline constexpr NumberRange kSamplesPerPixel{1, 1e9, true, ""};
inline constexpr NumberRange kThreads{0, 4096, true, ""};
inline constexpr NumberRange kReferenceSeed{0, 1.8e19, true, ""};
inline constexpr NumberRange kMaxScatter{0, 1e9, true, ""};
inline constexpr NumberRange kTimeSeconds{0, 1e9, false, "s"};

// Tone mapping: exposure [stops].
inline constexpr NumberRange kExposureStops{-30, 30, false, "stops"};

}  // namespace lucent::argument_ranges
