// slab.h: total diffuse reflectance and transmittance of a plane-parallel slab (or half-space) by Monte Carlo
// photon transport, like the tissue-optics tools researchers use (MCML: Wang, Jacques, Zheng 1995).
// Homogeneous medium with single-scattering albedo a, Henyey-Greenstein g, optical thickness b = sigma_t d,
// smooth Fresnel boundaries of relative index eta on both sides (total internal reflection included).
// Photons carry weights: boundary events split the weight into the escaping part (1 - F) and the reflected part F;
// absorption scales it by a per scattering; Russian roulette ends light photons without bias.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>

#include "transport/estimate.h"

namespace lucent::reference {

enum class Incidence { Normal, Diffuse };

struct SlabConfig {
  double albedo = 0.9;                                        // sigma_s / sigma_t
  double g = 0.0;                                             // Henyey-Greenstein mean cosine
  double eta = 1.0;                                           // n_medium / n_outside
  double thickness = std::numeric_limits<double>::infinity();  // optical thickness sigma_t d; inf = half-space
  Incidence incidence = Incidence::Normal;
  double incidence_deg = 0.0;                                 // angle of a collimated beam (Normal incidence)
  std::uint64_t photons = 1000000;
  std::uint64_t seed = 1;
  int threads = 0;                                            // 0 = all cores
  double roulette_threshold = 1e-3;  // weights below this play Russian roulette (survival 0.1)
};

struct SlabResult {
  Estimate specular_reflectance;         // reflected at the first surface, per incident power
  Estimate diffuse_reflectance;          // leaving the top after entering, per incident power
  Estimate diffuse_reflectance_per_refracted;  // the same per power that entered the medium
  Estimate transmittance;                // leaving the bottom, per incident power (includes unscattered)
  Estimate unscattered_transmittance;    // leaving the bottom without scattering, per incident power
  std::uint64_t photons = 0;
  double seconds = 0.0;
};

// Where refracted power leaves the lit surface: one escaping weight at lateral position (x, y) in units of
// 1 / sigma_t, the beam entering at the origin and travelling toward +x (its refracted direction lies in the x-z
// plane). Weights are per incident power, like SlabResult's: divide by 1 - specular for per refracted power.
struct SurfaceExit {
  double x = 0.0, y = 0.0, weight = 0.0;
};

// Photons run in fixed blocks of this many, each block on one thread; a sink sees the exits of one block in order.
inline constexpr std::uint64_t kSlabBlockPhotons = 4096;
inline std::size_t slab_block_count(const SlabConfig& config) {
  return static_cast<std::size_t>((config.photons + kSlabBlockPhotons - 1) / kSlabBlockPhotons);
}

// Receives the top-surface exits of block `block` (0 .. slab_block_count() - 1). Called concurrently for
// different blocks, never for one block from two threads: per-block tallies need no locks.
using SurfaceExitSink = std::function<void(std::size_t block, const SurfaceExit& exit)>;

// Throws lucent::Error naming the parameter when a value is out of range. `exits`, when given, sees every
// escape through the lit surface (the spatial profile that diffusion models approximate).
SlabResult simulate_slab(const SlabConfig& config, const SurfaceExitSink& exits = {});

}  // namespace lucent::reference
