// image_metrics.cpp: see image_metrics.h.
#include "image/image_metrics.h"

#include <algorithm>
#include <limits>
#include <cmath>

#include <fmt/format.h>

#include "lucent/error.h"
#include "shared/tonemap.h"

namespace lucent {

namespace {

void check_metric_input(const ImageRGBA32F& image, const std::string& what, bool negative_allowed) {
  static constexpr const char* kBands[3] = {"red", "green", "blue"};
  const std::size_t n = image.pixels.size() / 4;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c) {
      const float v = image.pixels[4 * i + c];
      if (std::isfinite(v) && (negative_allowed || v >= 0.0f)) continue;
      const std::size_t width = static_cast<std::size_t>(std::max(image.width, 1));
      throw Error(fmt::format("{} has {} {} at pixel ({}, {}), {}; no error metric is computed over it", what,
                              std::isfinite(v) ? "a negative value" : "a non-finite value", v, i % width, i / width,
                              kBands[c]));
    }
}

}  // namespace

ImageError image_error(const ImageRGBA32F& a, const ImageRGBA32F& b, const ImageRGBA32F* standard_error,
                       const MetricInputNames& names) {
  if (a.width != b.width || a.height != b.height)
    throw Error(fmt::format("images differ in size: {}x{} and {}x{}", a.width, a.height, b.width, b.height));
  check_metric_input(a, names.image, true);
  check_metric_input(b, names.reference, true);
  if (standard_error) check_metric_input(*standard_error, names.standard_error, false);
  ImageError e;
  double sum_sq[3] = {0, 0, 0}, sum_rel = 0.0, sum_err = 0.0, sum_var = 0.0, peak = 0.0;
  std::size_t n = a.pixels.size() / 4;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c) {
      double x = a.pixels[4 * i + c], y = b.pixels[4 * i + c], d = x - y;
      sum_sq[c] += d * d;
      sum_rel += d * d / (y * y + 1e-2);
      sum_err += d;
      peak = std::max(peak, y);
      if (standard_error) sum_var += double(standard_error->pixels[4 * i + c]) * standard_error->pixels[4 * i + c];
    }
  double mse_all = 0.0;
  for (int c = 0; c < 3; ++c) {
    e.rmse[c] = std::sqrt(sum_sq[c] / static_cast<double>(n));
    mse_all += sum_sq[c] / (3.0 * static_cast<double>(n));
  }
  e.rmse_rgb = std::sqrt((sum_sq[0] + sum_sq[1] + sum_sq[2]) / static_cast<double>(n));
  e.relative_mse = sum_rel / (3.0 * static_cast<double>(n));
  e.mean_error = sum_err / (3.0 * static_cast<double>(n));
  e.mean_error_se = std::sqrt(sum_var) / (3.0 * static_cast<double>(n));
  e.reference_noise_rms = std::sqrt(sum_var / (3.0 * static_cast<double>(n)));
  // Identical images: no error, an infinite PSNR. A black reference with a non-black image has no peak.
  e.psnr_db = mse_all == 0.0 ? std::numeric_limits<double>::infinity()
              : peak > 0.0   ? 10.0 * std::log10(peak * peak / mse_all)
                             : std::numeric_limits<double>::quiet_NaN();
  return e;
}

ImageRGBA32F tonemapped(const ImageRGBA32F& image, float exposure) {
  ImageRGBA32F out = image;
  float scale = std::exp2(exposure);
  // The ACES curve squares its input: past about 1e19 that overflows float to inf / inf = NaN. Its value at 1e6 is
  // already white, so larger inputs are held there.
  const float largest = 1e6f / scale;
  for (std::size_t i = 0; i < out.pixels.size(); i += 4) {
    const glm::vec3 linear(image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]);
    glm::vec3 v = shader::tonemap(glm::min(linear, glm::vec3(largest)), scale, LUCENT_TONEMAP_ACES);
    out.pixels[i] = v.x, out.pixels[i + 1] = v.y, out.pixels[i + 2] = v.z, out.pixels[i + 3] = 1.0f;
  }
  return out;
}

void check_displayable(const ImageRGBA32F& image, const std::string& name) {
  static constexpr const char* kBands[3] = {"red", "green", "blue"};
  const std::size_t width = static_cast<std::size_t>(std::max(image.width, 1));
  for (std::size_t i = 0; i < image.pixels.size() / 4; ++i)
    for (std::size_t c = 0; c < 3; ++c)
      if (std::isnan(image.pixels[4 * i + c]))
        throw Error(fmt::format("{} has a NaN at pixel ({}, {}), {}: it has no colour to display", name, i % width,
                                i / width, kBands[c]));
}

ImageError display_error(const ImageRGBA32F& a, const ImageRGBA32F& b, float exposure) {
  return display_values_error(tonemapped(a, exposure), tonemapped(b, exposure));
}

ImageError display_values_error(const ImageRGBA32F& a, const ImageRGBA32F& b) {
  ImageError e = image_error(a, b);
  // Peak 1 per channel.
  e.psnr_db = e.rmse_rgb > 0.0 ? 10.0 * std::log10(3.0 / (e.rmse_rgb * e.rmse_rgb))
                               : std::numeric_limits<double>::infinity();
  return e;
}

std::string psnr_text(double psnr_db) {
  if (std::isnan(psnr_db)) return "undefined (black reference)";
  if (std::isinf(psnr_db)) return "inf dB";
  return fmt::format("{:.2f} dB", psnr_db);
}

ImageRGBA32F from_srgb8(const ImageRGBA8& image, bool linear) {
  ImageRGBA32F out{image.width, image.height, std::vector<float>(image.pixels.size())};
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const float code = static_cast<float>(image.pixels[i]) / 255.0f;
    const bool colour = i % 4 != 3;
    out.pixels[i] = linear && colour ? (code <= 0.04045f ? code / 12.92f : std::pow((code + 0.055f) / 1.055f, 2.4f))
                                     : code;
  }
  return out;
}

ImageRGBA8 to_display(const ImageRGBA32F& image, float exposure) {
  ImageRGBA32F t = tonemapped(image, exposure);
  ImageRGBA8 out{image.width, image.height, std::vector<std::uint8_t>(t.pixels.size())};
  for (std::size_t i = 0; i < t.pixels.size(); ++i)
    out.pixels[i] = static_cast<std::uint8_t>(std::lround(std::clamp(t.pixels[i], 0.0f, 1.0f) * 255.0f));
  return out;
}

ImageRGBA8 heat_map(const ImageRGBA32F& a, const ImageRGBA32F& b, double scale) {
  ImageRGBA8 out{a.width, a.height, std::vector<std::uint8_t>(a.pixels.size())};
  for (std::size_t i = 0; i < a.pixels.size(); i += 4) {
    double d2 = 0.0;
    for (std::size_t c = 0; c < 3; ++c) d2 += std::pow(double(a.pixels[i + c]) - b.pixels[i + c], 2.0);
    double x = std::clamp(std::sqrt(d2) / scale, 0.0, 1.0);
    // black -> blue -> red -> yellow -> white
    double r = std::clamp(3.0 * x - 1.0, 0.0, 1.0), g = std::clamp(3.0 * x - 2.0, 0.0, 1.0);
    double bl = x < 1.0 / 3.0 ? 3.0 * x : std::clamp(2.0 - 3.0 * x, 0.0, 1.0) + std::clamp(3.0 * x - 2.0, 0.0, 1.0);
    out.pixels[i] = static_cast<std::uint8_t>(255.0 * r);
    out.pixels[i + 1] = static_cast<std::uint8_t>(255.0 * g);
    out.pixels[i + 2] = static_cast<std::uint8_t>(255.0 * std::min(1.0, bl));
    out.pixels[i + 3] = 255;
  }
  return out;
}

double noise_rgb(const ImageError& e) { return e.reference_noise_rms * std::sqrt(3.0); }

double corrected_rmse(const ImageError& e) {
  return std::sqrt(std::max(0.0, e.rmse_rgb * e.rmse_rgb - noise_rgb(e) * noise_rgb(e)));
}

}  // namespace lucent
