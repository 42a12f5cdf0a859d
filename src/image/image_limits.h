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

// The most bytes of pixel data a compressed image file can expand to, per byte of the file. Lossless image
// codecs stay far below it (deflate, PNG's and EXR's ZIP, at most 1032:1); a file that declares more pixel data
// than this could hold is refused before the pixels are allocated, since reading it would fail after the
// allocation anyway.
inline constexpr std::int64_t kMaxExpansionPerFileByte = 4096;

// "" when `data_bytes` of pixel data can come from a file of `file_bytes`, else the problem.
inline std::string pixel_data_problem(std::int64_t width, std::int64_t height, std::int64_t data_bytes,
                                      std::int64_t file_bytes) {
  if (file_bytes >= 0 && data_bytes / kMaxExpansionPerFileByte <= file_bytes) return "";
  return fmt::format("image is {}x{}, {} bytes of pixel data, more than a file of {} bytes can hold (at most {} "
                     "bytes a file byte)",
                     width, height, data_bytes, file_bytes, kMaxExpansionPerFileByte);
}

}  // namespace lucent
