// multipole_table.cpp: builds the multipole model's tables (layout and evaluation: bssrdf/multipole_table.h).
#include <algorithm>
#include <cmath>
#include <vector>

#include <atomic>
#include <thread>

#include "bssrdf/multipole.h"
#include "bssrdf/multipole_table.h"
#include "bssrdf/standard_dipole.h"
#include "materials/tabulated_bssrdf.h"

namespace lucent {
namespace {

using shader::kBssrdfTableHeader;
using shader::kBssrdfTableR;
using shader::kBssrdfTableRMin;

// The power one unit source at signed height z (toward the face it leaves through) sends out beyond radius r along
// that face, without alpha' / 2: the closed-form plane integral of z (1 + s d) e^(-s d) / d^3 from r outward,
// 2 pi z e^(-s d(r)) / d(r) / (2 pi), d(r) = sqrt(r^2 + z^2).
double power_beyond(double z, double r, double s) {
  if (z == 0.0) return 0.0;
  const double d = std::sqrt(r * r + z * z);
  return z * std::exp(-s * d) / d;
}

}  // namespace

std::vector<float> build_multipole_table(float alpha_prime, float eta, int depth_steps) {
  const double a = alpha_prime;
  const double s = std::sqrt(3.0 * (1.0 - a));  // sigma_tr / sigma_t'
  const double z_b = 2.0 * static_cast<double>(shader::standard_dipole_A(eta)) / 3.0;
  const double r_max = bssrdf_table_r_max(alpha_prime, 0.0f);
  std::vector<double> edges(static_cast<std::size_t>(kBssrdfTableR) + 1, 0.0);
  for (int k = 0; k < kBssrdfTableR; ++k) edges[static_cast<std::size_t>(k) + 1] = bssrdf_table_radial_edge(k, r_max);
  // Pairs of mirrored dipoles on each side: enough that the next pair's share is below 1e-7 of the first's, up to
  // 4096 (the thinnest, whitest slabs).
  std::vector<float> table(static_cast<std::size_t>(shader::kMultipoleTableFloats), 0.0f);
  // The radial coordinate's constants (bssrdf_table_r_coord's), so that a lookup costs one logarithm.
  const double q = std::log(r_max / kBssrdfTableRMin) / (kBssrdfTableR - 1);
  table[0] = static_cast<float>(r_max), table[1] = static_cast<float>(1.0 / q);
  table[2] = static_cast<float>(kBssrdfTableRMin * std::exp(0.5 * q));
  // Thickness nodes in turn on every core (std::thread: lucent_core uses no task library).
  auto node = [&](int j) {
    const double d = shader::multipole_table_thickness(j);
    const double period = 2.0 * (d + 2.0 * z_b);
    const int pairs = std::clamp(static_cast<int>(std::ceil(16.0 / std::max(1e-9, s * period))) + 2, 8, 4096);
    // top[e], bottom[e]: power beyond edge e through the top and the bottom face.
    std::vector<double> top(edges.size(), 0.0), bottom(edges.size(), 0.0);
    for (int step = 0; step < depth_steps; ++step) {
      // Depths clustered at both faces (z = d (1 - cos pi t) / 2): a source within r of a face puts its light
      // within about r of the point above or below it, so the small bins need sources that close to the faces.
      const double t = (step + 0.5) / depth_steps;
      const double z = 0.5 * d * (1.0 - std::cos(M_PI * t));
      const double w = 0.5 * d * M_PI * std::sin(M_PI * t) / depth_steps * std::exp(-z);  // dz times e^(-z)
      for (int i = -pairs; i <= pairs; ++i) {
        const double z_r = i * period + z, z_v = i * period - z - 2.0 * z_b;
        for (std::size_t e = 0; e < edges.size(); ++e) {
          top[e] += w * (power_beyond(z_r, edges[e], s) - power_beyond(z_v, edges[e], s));
          bottom[e] += w * (power_beyond(d - z_r, edges[e], s) - power_beyond(d - z_v, edges[e], s));
        }
      }
    }
    const double weight = 0.5 * a;
    float* R = &table[static_cast<std::size_t>(kBssrdfTableHeader + 2 * j * kBssrdfTableR)];
    float* T = R + kBssrdfTableR;
    // Within kMultipoleTableNearField of the entry point, the disk's mean (bssrdf/multipole_table.h).
    int near = 0;
    while (near + 1 < kBssrdfTableR && edges[static_cast<std::size_t>(near) + 1] < shader::kMultipoleTableNearField) ++near;
    const double disk = M_PI * edges[static_cast<std::size_t>(near) + 1] * edges[static_cast<std::size_t>(near) + 1];
    for (int k = 0; k < kBssrdfTableR; ++k) {
      const double area = M_PI * (edges[k + 1] * edges[k + 1] - edges[k] * edges[k]);
      R[k] = static_cast<float>(std::max(0.0, k <= near ? weight * (top[0] - top[near + 1]) / disk
                                                        : weight * (top[k] - top[k + 1]) / area));
      T[k] = static_cast<float>(std::max(0.0, k <= near ? weight * (bottom[0] - bottom[near + 1]) / disk
                                                        : weight * (bottom[k] - bottom[k + 1]) / area));
    }
    preserve_bssrdf_table_row_power(R, r_max);
    preserve_bssrdf_table_row_power(T, r_max);
  };
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int j = next++; j < shader::kMultipoleTableD; j = next++) node(j);
  };
  std::vector<std::thread> pool;
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  return table;
}

glm::vec2 multipole_table_totals(float alpha_prime, float eta, float optical_thickness) {
  const int offset = shader::bssrdf_table_offset(alpha_prime, shader::kMultipoleTableKey, eta);
  const double r_max = shader::bssrdf_table_value(offset);
  auto row_power = [&](int j, int row) {
    double power = 0.0;
    for (int k = 0; k < kBssrdfTableR; ++k) {
      const double inner = k == 0 ? 0.0 : bssrdf_table_radial_edge(k - 1, r_max);
      const double outer = k == 0 ? kBssrdfTableRMin : bssrdf_table_radial_edge(k, r_max);
      power += M_PI * (outer * outer - inner * inner) *
               shader::bssrdf_table_value(offset + kBssrdfTableHeader + (2 * j + row) * kBssrdfTableR + k);
    }
    return power;
  };
  const float d = optical_thickness > 0.0f ? optical_thickness : shader::kMultipoleTableDMax;
  const float dc = std::clamp(3.0f * std::log2(std::max(d, shader::kMultipoleTableDMin) / shader::kMultipoleTableDMin),
                              0.0f, static_cast<float>(shader::kMultipoleTableD - 1));
  const int j0 = std::min(static_cast<int>(dc), shader::kMultipoleTableD - 1), j1 = std::min(j0 + 1, shader::kMultipoleTableD - 1);
  const double f = dc - static_cast<float>(j0);
  return {static_cast<float>((1.0 - f) * row_power(j0, 0) + f * row_power(j1, 0)),
          static_cast<float>((1.0 - f) * row_power(j0, 1) + f * row_power(j1, 1))};
}

}  // namespace lucent
