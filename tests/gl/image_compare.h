// image_compare.h: golden-image comparison with a stated tolerance; writes the actual and a difference image
// on failure (never hashes).
#pragma once
#include <string>

#include "lucent/image.h"

namespace lucent::test {

struct ImageDifference {
  double mean_abs = 0.0;       // mean |a - b| over RGB, in 8-bit steps
  double mean_signed = 0.0;    // mean (a - b) over RGB: a systematic brightness change, noise averages out
  double percentile_99 = 0.0;  // 99th percentile of the per-pixel max-channel difference, 8-bit steps
  int max_abs = 0;
};

ImageDifference compare(const ImageRGBA8& actual, const ImageRGBA8& expected);
// |a - b| * 8 per channel, clamped, for looking at.
ImageRGBA8 difference_image(const ImageRGBA8& actual, const ImageRGBA8& expected);

// Test output folder (created), for actual/diff images and measurements.
std::string output_path(const std::string& name);

// A shared headless context for the GL tests of one process.
void ensure_gl_context();

// An embedded shader file's text without its #include lines, for tests that assemble a shader from shared headers
// in an order of their own (a failure when the file is not embedded).
std::string embedded_without_includes(const std::string& path);

// A linked compute program from GLSL source (the GL context current); a failure with the driver's log when it does
// not compile, and then 0.
unsigned compile_compute_source(const std::string& source);

}  // namespace lucent::test
