// image_limits.h: the largest image the readers accept, checked against the size a file declares before any
// pixel memory is allocated.
#pragma once
#include <cstdint>
#include <string>

#include <fmt/format.h>

namespace lucent {

// 16384 x 16384 pixels: 4 GiB as RGBA floats. Larger than any environment map or render lucent uses.
inline constexpr std::int64_t kMaxImagePixels = std::int64_t{1} << 28;

// "" when a declared width x height is acceptable, else the problem, for the reader's message.
inline std::string image_size_problem(std::int64_t width, std::int64_t height) {
  if (width <= 0 || height <= 0) return fmt::format("image is {}x{}", width, height);
  if (width > kMaxImagePixels / height)
    return fmt::format("image is {}x{}, more than the {} pixels (16384 x 16384) lucent reads", width, height,
                       kMaxImagePixels);
  return "";
}

}  // namespace lucent
