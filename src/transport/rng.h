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

  // The generator of one camera path: (seed, pixel, sample) hashed into PCG's starting state and stream. PCG's
  // streams are related to each other (an increment differing in a few high bits, as pixel << 24 gave, yields a
  // sequence that is an affine image of the other), and consecutive seeds started neighbouring states on the same
  // streams; hashing every input makes each path's numbers independent of every other's for all practical
  // purposes, which the reported standard error assumes.
  static Rng for_path(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample) {
    const std::uint64_t key = mix(mix(seed) ^ pixel) ^ sample;
    return Rng(mix(key ^ 0x9e3779b97f4a7c15ULL), mix(key));
  }

  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(next()) * (1.0 / 4294967296.0); }

  // A generator for a side computation (a next-event estimate) keyed on this one's state, which it does not advance:
  // the numbers the path draws stay those it would draw without the side computation, whatever that draws.
  Rng split() const { return Rng(mix(state_ ^ 0x5851f42d4c957f2dULL), mix(state_ + increment_)); }

 private:
  // SplitMix64's finalizer (Steele, Lea and Flood 2014): a bijection of 64-bit integers with full avalanche.
  static std::uint64_t mix(std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30u)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27u)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31u);
  }

  std::uint64_t state_ = 0;
  std::uint64_t increment_;
};

}  // namespace lucent::reference
