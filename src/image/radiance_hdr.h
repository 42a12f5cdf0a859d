// radiance_hdr.h: Radiance RGBE pictures (.hdr) read with every length checked against the data, so that a
// truncated or hostile file ends in an error, not in a hang or a read past the end. Format: Greg Ward, "Real
// Pixels" (Graphics Gems II, 1991) and the Radiance file format notes (header, "-Y H +X W" resolution line,
// flat or run-length encoded scanlines).
#pragma once
#include <string>
#include <string_view>

#include "lucent/image.h"

namespace lucent {

// Decodes a picture held in memory: first line "#?RADIANCE" or "#?RGBE", header lines up to a blank line
// (FORMAT must be 32-bit_rle_rgbe when given), the resolution line "-Y H +X W" (top row first), then H
// scanlines, each flat (4 bytes a pixel) or run-length encoded per channel. A pixel (r, g, b, e) is
// (r, g, b) 2^(e - 136), and 0 when e = 0, as stb_image decodes it; alpha is 1. Throws std::runtime_error with
// the problem (the caller names the file) when the data is malformed or truncated, or the image is larger than
// kMaxImagePixels (image_limits.h): that check comes before the pixels are allocated.
ImageRGBA32F decode_radiance_hdr(std::string_view data);

// Reads a file and decodes it; the problem in std::runtime_error, as above.
ImageRGBA32F read_radiance_hdr_file(const std::string& path);

}  // namespace lucent
