// tabulated_bssrdf.cpp: see tabulated_bssrdf.h.
#include "materials/tabulated_bssrdf.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>

#include <fmt/format.h>

#include "bssrdf/fresnel.h"
#include "bssrdf/multipole_table.h"
#include "bssrdf/tabulated.h"
#include "cache/precompute_cache.h"
#include "lucent/error.h"
#include "transport/slab.h"

namespace lucent {
namespace {

using shader::kBssrdfTableCapacity;
using shader::kBssrdfTableDirectory;
using shader::kBssrdfTableFloats;
using shader::kBssrdfTableHeader;
using shader::kBssrdfTablePhi;
using shader::kBssrdfTableR;
using shader::kBssrdfTableRMin;
using shader::kBssrdfTableTheta;
using shader::kBssrdfTableThetaMaxDeg;

// Bumped whenever the tables' content changes for the same medium (part of the cache key).
constexpr std::uint32_t kTableFormatVersion = 4;

double radial_edge(int k, double r_max) { return bssrdf_table_radial_edge(k, r_max); }

// Radial bin of reduced radius r; kBssrdfTableR when beyond r_max.
int radial_bin(double r, double r_max) {
  if (r < kBssrdfTableRMin) return 0;
  if (r >= r_max) return kBssrdfTableR;
  const double q = std::log(r_max / kBssrdfTableRMin) / (kBssrdfTableR - 1);
  return std::min(kBssrdfTableR - 1, 1 + static_cast<int>(std::log(r / kBssrdfTableRMin) / q));
}

// The process's table array: capacity fixed at first use, so that pointers into it stay valid. A table's
// floats are written before the directory entry that names it, and count_ is published last.
class TableStore {
 public:
  TableStore() : data_(static_cast<std::size_t>(kBssrdfTableDirectory + kBssrdfTableCapacity * kBssrdfTableFloats)) {}

  // The offset of a table whose key matches within the shaders' tolerance (bssrdf/tabulated.h); -1 if none.
  int find(float albedo, float g, float eta) const {
    const int count = count_.load(std::memory_order_acquire);
    for (int k = 0; k < count; ++k) {
      const float* e = &data_[static_cast<std::size_t>(1 + 4 * k)];
      if (std::abs(e[0] - albedo) <= 1e-5f * albedo && std::abs(e[1] - g) <= 1e-6f && std::abs(e[2] - eta) <= 1e-6f)
        return static_cast<int>(e[3]);
    }
    return -1;
  }

  int find_or_build(float albedo, float g, float eta) {
    if (int offset = find(albedo, g, eta); offset >= 0) return offset;
    const std::lock_guard lock(mutex_);
    if (int offset = find(albedo, g, eta); offset >= 0) return offset;
    const int count = count_.load(std::memory_order_relaxed);
    if (count >= kBssrdfTableCapacity)
      throw Error(fmt::format("the tabulated and multipole models hold at most {} distinct band media in one process",
                              kBssrdfTableCapacity));
    BssrdfTableStats stats;
    std::vector<float> table = load_or_build(albedo, g, eta, stats);
    const int offset = kBssrdfTableDirectory + count * kBssrdfTableFloats;
    std::copy(table.begin(), table.end(), data_.begin() + offset);
    float* e = &data_[static_cast<std::size_t>(1 + 4 * count)];
    e[0] = albedo, e[1] = g, e[2] = eta, e[3] = static_cast<float>(offset);
    data_[0] = static_cast<float>(count + 1);
    last_stats_ = stats;
    count_.store(count + 1, std::memory_order_release);
    generation_.fetch_add(1, std::memory_order_acq_rel);
    return offset;
  }

  float value(int i) const { return data_[static_cast<std::size_t>(i)]; }
  std::span<const float> in_use() const {
    return {data_.data(), static_cast<std::size_t>(kBssrdfTableDirectory +
                                                   count_.load(std::memory_order_acquire) * kBssrdfTableFloats)};
  }
  std::uint64_t generation() const { return generation_.load(std::memory_order_acquire); }
  BssrdfTableStats last_stats() {
    const std::lock_guard lock(mutex_);
    return last_stats_;
  }

 private:
  static std::vector<float> load_or_build(float albedo, float g, float eta, BssrdfTableStats& stats) {
    if (g == shader::kMultipoleTableKey) {  // closed forms: a fraction of a second, not worth a cache entry
      const auto start = std::chrono::steady_clock::now();
      std::vector<float> table = build_multipole_table(albedo, eta);
      table.resize(static_cast<std::size_t>(kBssrdfTableFloats), 0.0f);
      stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return table;
    }
    cache::Key key("bssrdf-table", kTableFormatVersion);
    const std::uint64_t photons = bssrdf_table_photons();
    key.number(albedo).number(g).number(eta).integer(static_cast<std::int64_t>(photons));
    if (auto bytes = cache::load(key); bytes && bytes->size() == kBssrdfTableFloats * sizeof(float)) {
      std::vector<float> table(static_cast<std::size_t>(kBssrdfTableFloats));
      std::memcpy(table.data(), bytes->data(), bytes->size());
      stats.from_cache = true;
      return table;
    }
    std::vector<float> table;
    table = build_bssrdf_table(albedo, g, eta, photons, &stats);  // its own threads; other callers wait on the lock
    std::fprintf(stderr,
                 "lucent: tabulated the half-space BSSRDF of albedo %.6g, g %.4g, eta %.4g in %.1f s (reflectance "
                 "%.4f at normal incidence, %.2g of it beyond the table)\n",
                 static_cast<double>(albedo), static_cast<double>(g), static_cast<double>(eta), stats.seconds, stats.total,
                 stats.tail_fraction);
    cache::store(key, std::as_bytes(std::span<const float>(table)));
    return table;
  }

  std::vector<float> data_;
  std::atomic<int> count_{0};
  std::atomic<std::uint64_t> generation_{0};
  std::mutex mutex_;
  BssrdfTableStats last_stats_;
};

std::atomic<std::uint64_t> g_photons_per_node{kBssrdfTablePhotons};

TableStore& store() {
  static TableStore instance;
  return instance;
}

// Bin averages interpolated between bin centres do not integrate to the bins' sum where the profile is steep (near
// the entry point it falls like 1/r): about 1.5% short over a whole table. Rescales each radial row (values at
// `row`) so that the interpolation the evaluation uses (bssrdf_table_radial) carries exactly the row's power.
}  // namespace

double bssrdf_table_radial_edge(int k, double r_max) {
  const double q = std::log(r_max / kBssrdfTableRMin) / (kBssrdfTableR - 1);
  return kBssrdfTableRMin * std::exp(k * q);
}

void preserve_bssrdf_table_row_power(float* row, double r_max) {
  double binned = 0.0;
  for (int k = 0; k < kBssrdfTableR; ++k) {
    const double inner = k == 0 ? 0.0 : radial_edge(k - 1, r_max), outer = k == 0 ? kBssrdfTableRMin : radial_edge(k, r_max);
    binned += row[k] * 0.5 * (outer * outer - inner * inner);
  }
  if (binned <= 0.0) return;
  auto interpolated = [&](double r) {
    const double u = shader::bssrdf_table_r_coord(static_cast<float>(r), static_cast<float>(r_max));
    const int i0 = std::min(static_cast<int>(u), kBssrdfTableR - 1), i1 = std::min(i0 + 1, kBssrdfTableR - 1);
    return row[i0] + (u - i0) * (row[i1] - row[i0]);
  };
  // Integral of f(r) r dr: midpoint rule in log r from 1e-4 r'_min, plus the disk inside it.
  constexpr int kSteps = 20000;
  const double r0 = 1e-4 * kBssrdfTableRMin, du = std::log(r_max / r0) / kSteps;
  double integral = 0.5 * r0 * r0 * interpolated(0.0);
  for (int s = 0; s < kSteps; ++s) {
    const double r = r0 * std::exp((s + 0.5) * du);
    integral += interpolated(r) * r * r * du;
  }
  if (integral <= 0.0) return;
  const double scale = binned / integral;
  for (int k = 0; k < kBssrdfTableR; ++k) row[k] = static_cast<float>(row[k] * scale);
}

void set_bssrdf_table_photons(std::uint64_t photons_per_node) {
  g_photons_per_node.store(std::max<std::uint64_t>(1, photons_per_node));
}
std::uint64_t bssrdf_table_photons() { return g_photons_per_node.load(); }

float bssrdf_table_r_max(float albedo, float g) {
  const double a_prime = albedo * (1.0 - g) / (1.0 - albedo * g);  // reduced albedo sigma_s' / sigma_t'
  const double diffusion_length = 1.0 / std::sqrt(std::max(1e-12, 3.0 * (1.0 - a_prime)));
  return static_cast<float>(std::clamp(25.0 * diffusion_length, 8.0, 4000.0));
}

std::vector<float> build_bssrdf_table(float albedo, float g, float eta, std::uint64_t photons_per_node,
                                      BssrdfTableStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  const double r_max = bssrdf_table_r_max(albedo, g);
  const double reduced = 1.0 - static_cast<double>(albedo) * g;  // sigma_t' / sigma_t: slab lengths to reduced
  const double dphi = M_PI / kBssrdfTablePhi;
  const int bins = kBssrdfTablePhi * kBssrdfTableR;
  std::vector<float> table(static_cast<std::size_t>(kBssrdfTableFloats), 0.0f);
  table[0] = static_cast<float>(r_max);
  for (int t = 0; t < kBssrdfTableTheta; ++t) {
    reference::SlabConfig config;
    config.albedo = albedo, config.g = g, config.eta = eta;
    config.incidence_deg = static_cast<double>(kBssrdfTableThetaMaxDeg) * t / (kBssrdfTableTheta - 1);
    config.photons = photons_per_node;
    config.seed = 0x7ab1e000u + static_cast<std::uint64_t>(t);
    // Per-block histograms (bins, then the tail beyond r_max), summed in block order: deterministic.
    std::vector<std::vector<double>> blocks(reference::slab_block_count(config), std::vector<double>(bins + 1, 0.0));
    const reference::SlabResult result =
        reference::simulate_slab(config, [&](std::size_t block, const reference::SurfaceExit& exit) {
          const double r = std::hypot(exit.x, exit.y) * reduced;
          const int k = radial_bin(r, r_max);
          const int p = std::min(kBssrdfTablePhi - 1, static_cast<int>(std::atan2(std::abs(exit.y), exit.x) / dphi));
          blocks[block][k == kBssrdfTableR ? bins : p * kBssrdfTableR + k] += exit.weight;
        });
    std::vector<double> sum(bins + 1, 0.0);
    for (const auto& b : blocks)
      for (int i = 0; i <= bins; ++i) sum[i] += b[i];
    const double refracted = static_cast<double>(photons_per_node) * (1.0 - result.specular_reflectance.mean);
    double total = 0.0;
    for (int p = 0; p < kBssrdfTablePhi; ++p)
      for (int k = 0; k < kBssrdfTableR; ++k) {
        const double inner = k == 0 ? 0.0 : radial_edge(k - 1, r_max), outer = k == 0 ? kBssrdfTableRMin : radial_edge(k, r_max);
        const double area = (outer * outer - inner * inner) * dphi;  // both sides of the plane of incidence
        const double w = sum[p * kBssrdfTableR + k] / refracted;
        total += w;
        table[static_cast<std::size_t>(kBssrdfTableHeader + (t * kBssrdfTablePhi + p) * kBssrdfTableR + k)] =
            static_cast<float>(w / area);
      }
    // Normal incidence is symmetric about the normal: every azimuth row is the same profile (pooling the rows
    // divides their variance by kBssrdfTablePhi; a single noisy row read at the one azimuth a flat plane gives made
    // the flat total 1.5% short).
    if (t == 0) {
      float* node = &table[static_cast<std::size_t>(kBssrdfTableHeader + t * kBssrdfTablePhi * kBssrdfTableR)];
      for (int k = 0; k < kBssrdfTableR; ++k) {
        double mean = 0.0;
        for (int p = 0; p < kBssrdfTablePhi; ++p) mean += node[p * kBssrdfTableR + k];
        for (int p = 0; p < kBssrdfTablePhi; ++p) node[p * kBssrdfTableR + k] = static_cast<float>(mean / kBssrdfTablePhi);
      }
    }
    for (int p = 0; p < kBssrdfTablePhi; ++p)
      preserve_bssrdf_table_row_power(&table[static_cast<std::size_t>(kBssrdfTableHeader + (t * kBssrdfTablePhi + p) * kBssrdfTableR)],
                         r_max);
    if (t == 0 && stats) {
      stats->tail_fraction = sum[bins] / refracted;
      stats->total = total + stats->tail_fraction;
    }
  }
  if (stats) stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return table;
}

void prepare_bssrdf_tables(const Material& material) {
  for (int band = 0; band < 3; ++band) {
    const float sigma_t = material.sigma_a[band] + material.sigma_s[band];
    if (material.model == BssrdfModel::Tabulated)
      store().find_or_build(material.sigma_s[band] / sigma_t, material.g[band], material.eta);
    if (material.model == BssrdfModel::Multipole) {
      // The reduced albedo as make_band_medium computes it, so that the shaders' search finds it.
      const shader::BandMedium m = shader::make_band_medium(material.sigma_a[band], material.sigma_s[band], material.g[band]);
      store().find_or_build(m.alpha_prime, shader::kMultipoleTableKey, material.eta);
    }
  }
}

std::vector<float> bssrdf_table_array() {
  const std::span<const float> in_use = store().in_use();
  std::vector<float> gpu(in_use.begin(), in_use.end());
  const int count = static_cast<int>(gpu[0]);
  struct Entry {
    float a, g, eta, offset;
  };
  std::vector<Entry> entries(static_cast<std::size_t>(kBssrdfTableCapacity),
                             Entry{shader::kBssrdfTableUnusedAlbedo, 0.0f, 0.0f, -1.0f});
  for (int k = 0; k < count; ++k) {
    const float* e = &gpu[static_cast<std::size_t>(1 + 4 * k)];
    entries[static_cast<std::size_t>(k)] = {e[0], e[1], e[2], e[3]};
  }
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& x, const Entry& y) { return x.a < y.a; });
  // The shaders check kBssrdfTableSameAlbedo entries from the first whose albedo is within 1e-5 of theirs.
  for (int k = 0; k + shader::kBssrdfTableSameAlbedo < count; ++k)
    if (entries[static_cast<std::size_t>(k + shader::kBssrdfTableSameAlbedo)].a -
            entries[static_cast<std::size_t>(k)].a <=
        2e-5f * entries[static_cast<std::size_t>(k)].a)
      throw Error(fmt::format("the tabulated and multipole models tell at most {} band media of one albedo ({}) "
                              "apart on the GPU",
                              shader::kBssrdfTableSameAlbedo, entries[static_cast<std::size_t>(k)].a));
  for (std::size_t k = 0; k < entries.size(); ++k) {
    float* e = &gpu[1 + 4 * k];
    e[0] = entries[k].a, e[1] = entries[k].g, e[2] = entries[k].eta, e[3] = entries[k].offset;
  }
  return gpu;
}
std::uint64_t bssrdf_table_generation() { return store().generation(); }
BssrdfTableStats last_bssrdf_table_stats() { return store().last_stats(); }

namespace shader {

int bssrdf_table_offset(float albedo, float g, float eta) {
  thread_local float last_albedo = -1.0f, last_g = 0.0f, last_eta = 0.0f;
  thread_local int last_offset = -1;
  if (albedo == last_albedo && g == last_g && eta == last_eta) return last_offset;
  const int offset = store().find_or_build(albedo, g, eta);
  last_albedo = albedo, last_g = g, last_eta = eta, last_offset = offset;
  return offset;
}

float bssrdf_table_value(int i) { return store().value(i); }

}  // namespace shader
}  // namespace lucent
