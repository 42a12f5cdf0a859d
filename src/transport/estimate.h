// estimate.h: Monte Carlo means with standard errors, accumulated from per-sample values.
#pragma once
#include <cmath>
#include <cstdint>

namespace lucent::reference {

struct Estimate {
  double mean = 0.0;
  double standard_error = 0.0;
};

class Accumulator {
 public:
  void add(double x) { sum_ += x, sum2_ += x * x, ++n_; }
  void merge(const Accumulator& o) { sum_ += o.sum_, sum2_ += o.sum2_, n_ += o.n_; }
  std::uint64_t count() const { return n_; }
  Estimate estimate() const {
    if (n_ == 0) return {};
    double n = static_cast<double>(n_), mean = sum_ / n;
    double variance = n > 1 ? std::max(0.0, (sum2_ - n * mean * mean) / (n - 1.0)) : 0.0;
    return {mean, std::sqrt(variance / n)};
  }

 private:
  double sum_ = 0.0, sum2_ = 0.0;
  std::uint64_t n_ = 0;
};

}  // namespace lucent::reference
