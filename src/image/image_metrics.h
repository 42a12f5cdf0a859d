// image_metrics.h: error of an image against a reference: RMSE per channel, Dal Corso et al.'s
// sqrt(dr^2 + dg^2 + db^2) (Fig. 8), relative MSE, mean error with its standard error (when the reference
// carries one), PSNR, on linear and on tone-mapped values; and a heat-map difference image.
#pragma once
#include <string>

#include "lucent/image.h"

namespace lucent {

struct ImageError {
  double rmse[3] = {0, 0, 0};      // per channel
  double rmse_rgb = 0.0;           // sqrt(mean over pixels of dr^2 + dg^2 + db^2)
  double relative_mse = 0.0;       // mean of (a - b)^2 / (b^2 + 1e-2) over pixels and channels
  double mean_error = 0.0;         // mean of (a - b) over pixels and channels
  double mean_error_se = 0.0;      // its standard error from the reference's per-pixel errors (0 if none)
  // 10 log10(peak^2 / MSE), peak = max of the reference (1 for display values); +inf for identical images, NaN
  // when the reference is black and the image is not (no peak to measure against).
  double psnr_db = 0.0;
  double reference_noise_rms = 0.0;  // RMS of the reference's per-pixel standard error (0 if none)
};

// The noise of a reference in the units of the RGB RMSE (sqrt(dr^2+dg^2+db^2)), and the noise-corrected RMSE:
// the expected squared error against a noisy reference is the method's squared error plus the reference's variance.
double noise_rgb(const ImageError& e);
double corrected_rmse(const ImageError& e);

// How image_error's messages name its inputs (file names in `compare`, runs in `bench`).
struct MetricInputNames {
  std::string image = "the image", reference = "the reference", standard_error = "the reference's standard error";
};

// `standard_error` may be null. Both images must have the same size, and every red, green and blue value finite
// (and the standard error's not negative): otherwise throws lucent::Error naming the input, the first such pixel
// (x, y from the top left) and its band, since a metric over it would be NaN, or a NaN would compare as no error.
ImageError image_error(const ImageRGBA32F& a, const ImageRGBA32F& b, const ImageRGBA32F* standard_error = nullptr,
                       const MetricInputNames& names = {});
// The same on tone-mapped values in [0, 1] (exposure in stops, ACES, sRGB); values too large for the tone curve's
// float arithmetic (beyond 1e6 after exposure) display as white.
ImageError display_error(const ImageRGBA32F& a, const ImageRGBA32F& b, float exposure);
// The same on display values already in [0, 1] (an 8-bit image's codes / 255).
ImageError display_values_error(const ImageRGBA32F& a, const ImageRGBA32F& b);
// "24.31 dB", "inf dB" (identical), "undefined (black reference)".
std::string psnr_text(double psnr_db);
// An 8-bit sRGB image as floats: `linear` decodes the sRGB curve (IEC 61966-2-1) to display light in [0, 1];
// otherwise the codes / 255, the values a display shows. Alpha / 255 either way.
ImageRGBA32F from_srgb8(const ImageRGBA8& image, bool linear);
ImageRGBA32F tonemapped(const ImageRGBA32F& image, float exposure);  // display values in [0, 1]
// Throws lucent::Error naming `name`, the first NaN's pixel and band: a NaN has no colour to display (the tone
// curve would turn it black without a word). +inf displays as white.
void check_displayable(const ImageRGBA32F& image, const std::string& name);
ImageRGBA8 to_display(const ImageRGBA32F& image, float exposure);    // tone-mapped 8-bit
// |a - b| per pixel (sqrt(dr^2+dg^2+db^2)) as a heat map (black, blue, red, yellow, white) scaled to `scale`.
ImageRGBA8 heat_map(const ImageRGBA32F& a, const ImageRGBA32F& b, double scale);

}  // namespace lucent
