// rng.h: the CPU references' random numbers: PCG32 (O'Neill 2014), one stream per (seed, path), so that a
// render or a photon simulation is deterministic whatever the thread schedule, and any path can be replayed.
#pragma once
#include <cstdint>

namespace lucent::reference {

class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream) : increment_((stream << 1u) | 1u) {
    next();
    state_ += seed;
    next();
  }

  std::uint32_t next() {
    std::uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + increment_;
    auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    auto rotation = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rotation) | (xorshifted << ((32u - rotation) & 31u));
  }

  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(next()) * (1.0 / 4294967296.0); }

 private:
  std::uint64_t state_ = 0;
  std::uint64_t increment_;
};

}  // namespace lucent::reference
