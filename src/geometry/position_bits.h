// position_bits.h: a position as the bits of its coordinates, a key that welds vertices sitting at exactly the same
// place (vertices split along texture seams or normal creases) and tells every other pair apart; -0 and +0 are one.
#pragma once
#include <array>
#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>

namespace lucent {

inline std::array<std::uint32_t, 3> position_bits(glm::vec3 p) {
  std::array<std::uint32_t, 3> bits{};
  for (int a = 0; a < 3; ++a) {
    const float f = p[a] == 0.0f ? 0.0f : p[a];
    std::memcpy(&bits[static_cast<std::size_t>(a)], &f, sizeof(f));
  }
  return bits;
}

}  // namespace lucent
