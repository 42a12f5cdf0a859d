// slab.cpp: see slab.h.
#include "transport/slab.h"

#include <chrono>
#include <cmath>
#include <vector>

#include <algorithm>
#include <atomic>
#include <thread>

#include <fmt/format.h>

#include "bssrdf/fresnel.h"
#include "lucent/error.h"
#include "transport/random_walk.h"

namespace lucent::reference {
namespace {

struct PhotonTally {
  double specular = 0.0, reflected = 0.0, transmitted = 0.0, unscattered = 0.0, refracted = 0.0;
};

struct BlockTally {
  Accumulator specular, reflected, reflected_per_refracted, transmitted, unscattered;
  void add(const PhotonTally& t) {
    specular.add(t.specular), reflected.add(t.reflected), transmitted.add(t.transmitted);
    unscattered.add(t.unscattered);
    reflected_per_refracted.add(t.refracted > 0.0 ? t.reflected / t.refracted : 0.0);
  }
  void merge(const BlockTally& o) {
    specular.merge(o.specular), reflected.merge(o.reflected), transmitted.merge(o.transmitted);
    unscattered.merge(o.unscattered), reflected_per_refracted.merge(o.reflected_per_refracted);
  }
};

void check(bool ok, const std::string& what) {
  if (!ok) throw Error(what);
}

// One photon: z is depth (0 at the lit surface, growing into the medium), sigma_t = 1.
PhotonTally trace_photon(const SlabConfig& c, Rng& rng, const SurfaceExitSink& exits, std::size_t block) {
  PhotonTally t;
  double cos_i = c.incidence == Incidence::Normal ? std::cos(c.incidence_deg * M_PI / 180.0)
                                                 : std::sqrt(rng.uniform());  // diffuse: cosine-weighted
  double F = shader::fresnel_reflectance(static_cast<float>(c.eta), static_cast<float>(cos_i));
  t.specular = F;
  double weight = 1.0 - F;
  t.refracted = weight;
  double sin_t = std::sqrt(1.0 - cos_i * cos_i) / c.eta;
  glm::dvec3 dir(sin_t, 0.0, std::sqrt(std::max(0.0, 1.0 - sin_t * sin_t)));
  double x = 0.0, y = 0.0, z = 0.0;
  bool scattered = false;
  while (weight > 0.0) {
    double s = sample_free_flight(rng, 1.0);
    bool leaves_bottom = dir.z > 0.0 && z + s * dir.z >= c.thickness;
    bool leaves_top = dir.z < 0.0 && z + s * dir.z <= 0.0;
    if (leaves_bottom || leaves_top) {
      // Boundary: the escaping part leaves, the Fresnel-reflected part continues mirrored.
      const double to_boundary = ((leaves_bottom ? c.thickness : 0.0) - z) / dir.z;
      x += to_boundary * dir.x, y += to_boundary * dir.y;
      z = leaves_bottom ? c.thickness : 0.0;
      double R = shader::fresnel_reflectance(static_cast<float>(1.0 / c.eta), static_cast<float>(std::abs(dir.z)));
      double escaping = weight * (1.0 - R);
      if (leaves_top) t.reflected += escaping;
      if (leaves_top && exits) exits(block, SurfaceExit{x, y, escaping});
      if (leaves_bottom) t.transmitted += escaping, t.unscattered += scattered ? 0.0 : escaping;
      weight *= R;
      dir.z = -dir.z;
    } else {
      x += s * dir.x, y += s * dir.y, z += s * dir.z;
      weight *= c.albedo;
      dir = sample_henyey_greenstein(rng, dir, c.g);
      scattered = true;
    }
    if (!russian_roulette(rng, weight, c.roulette_threshold)) break;
  }
  return t;
}

}  // namespace

SlabResult simulate_slab(const SlabConfig& c, const SurfaceExitSink& exits) {
  check(c.albedo >= 0.0 && c.albedo <= 1.0, fmt::format("--albedo {} is out of range; allowed range [0, 1]", c.albedo));
  check(c.g > -1.0 && c.g < 1.0, fmt::format("--g {} is out of range; allowed range (-1, 1)", c.g));
  check(c.eta >= 1.0 && c.eta <= 3.0, fmt::format("--eta {} is out of range; allowed range [1, 3]", c.eta));
  check(c.thickness > 0.0, fmt::format("--thickness {} must be positive (optical thickness) or inf", c.thickness));
  check(c.photons > 0, "--photons must be positive");
  check(c.incidence_deg >= 0.0 && c.incidence_deg < 90.0,
        fmt::format("--incidence-deg {} is out of range; allowed range [0, 90)", c.incidence_deg));
  auto start = std::chrono::steady_clock::now();
  // Fixed blocks, each with its own random streams, summed in order: identical results for any thread count.
  const std::uint64_t block_size = kSlabBlockPhotons;
  std::size_t blocks = slab_block_count(c);
  std::vector<BlockTally> tallies(blocks);
  // Worker threads take blocks in turn (std::thread: this physics lives in lucent_core, which uses no task library).
  const unsigned threads = c.threads > 0 ? static_cast<unsigned>(c.threads) : std::max(1u, std::thread::hardware_concurrency());
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t b; (b = next.fetch_add(1)) < blocks;) {
      std::uint64_t first = b * block_size, last = std::min(c.photons, first + block_size);
      for (std::uint64_t i = first; i < last; ++i) {
        Rng rng(c.seed, i);
        tallies[b].add(trace_photon(c, rng, exits, b));
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < std::min<std::size_t>(threads, blocks); ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  BlockTally total;
  for (const BlockTally& t : tallies) total.merge(t);
  SlabResult r;
  r.specular_reflectance = total.specular.estimate();
  r.diffuse_reflectance = total.reflected.estimate();
  r.diffuse_reflectance_per_refracted = total.reflected_per_refracted.estimate();
  r.transmittance = total.transmitted.estimate();
  r.unscattered_transmittance = total.unscattered.estimate();
  r.photons = c.photons;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace lucent::reference
