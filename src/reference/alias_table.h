// alias_table.h: sampling an index i with probability w_i / sum(w) in O(1) (Walker's alias method, built by
// Vose's algorithm). Each column j keeps its own index with probability `keep[j]` and otherwise gives `alias[j]`;
// a sample costs one column lookup, where a binary search of a CDF costs log2(n) scattered loads (the CPU
// references draw millions of area samples per second from meshes of 10^5 triangles).
#pragma once
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace lucent::reference {

class AliasTable {
 public:
  AliasTable() = default;
  // Weights must be non-negative with a positive sum.
  explicit AliasTable(const std::vector<double>& weights) {
    const std::size_t n = weights.size();
    double total = 0.0;
    for (double w : weights) {
      if (!(w >= 0.0)) throw std::invalid_argument("AliasTable: a weight is negative or NaN");
      total += w;
    }
    if (n == 0 || !(total > 0.0)) throw std::invalid_argument("AliasTable: the weights sum to zero");
    keep_.assign(n, 1.0);
    alias_.resize(n);
    std::vector<double> scaled(n);
    std::vector<std::uint32_t> small, large;
    for (std::size_t i = 0; i < n; ++i) {
      scaled[i] = weights[i] * static_cast<double>(n) / total;
      alias_[i] = static_cast<std::uint32_t>(i);
      (scaled[i] < 1.0 ? small : large).push_back(static_cast<std::uint32_t>(i));
    }
    while (!small.empty() && !large.empty()) {
      const std::uint32_t s = small.back(), l = large.back();
      small.pop_back();
      keep_[s] = scaled[s];
      alias_[s] = l;
      scaled[l] -= 1.0 - scaled[s];
      if (scaled[l] < 1.0) {
        large.pop_back();
        small.push_back(l);
      }
    }
    // Whatever is left holds 1 up to rounding: it keeps its own index.
  }

  std::size_t size() const { return keep_.size(); }

  // u0 chooses the column, u1 the coin; both uniform in [0, 1).
  std::size_t sample(double u0, double u1) const {
    const std::size_t n = keep_.size();
    if (n == 0) throw std::logic_error("AliasTable: sampling an empty table");
    std::size_t j = static_cast<std::size_t>(u0 * static_cast<double>(n));
    if (j >= n) j = n - 1;
    return u1 < keep_[j] ? j : alias_[j];
  }

  // The probability the table gives index i (for tests: it equals w_i / sum(w) up to rounding).
  double probability(std::size_t i) const {
    const double n = static_cast<double>(keep_.size());
    double p = keep_[i] / n;
    for (std::size_t j = 0; j < keep_.size(); ++j)
      if (alias_[j] == i && j != i) p += (1.0 - keep_[j]) / n;
    return p;
  }

 private:
  std::vector<double> keep_;
  std::vector<std::uint32_t> alias_;
};

}  // namespace lucent::reference
