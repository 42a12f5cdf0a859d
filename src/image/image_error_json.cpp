// image_error_json.cpp: ImageError fields by name.
#include "image/image_error_json.h"

#include <cmath>

namespace lucent {

// JSON has no infinity or NaN: psnr_db is null for identical images and for a black reference, and "psnr" says which.
nlohmann::json to_json(const ImageError& e) {
  const nlohmann::json psnr_db = std::isfinite(e.psnr_db) ? nlohmann::json(e.psnr_db) : nlohmann::json(nullptr);
  return {{"rmse", {e.rmse[0], e.rmse[1], e.rmse[2]}}, {"rmse_rgb", e.rmse_rgb},
          {"relative_mse", e.relative_mse},             {"mean_error", e.mean_error},
          {"mean_error_se", e.mean_error_se},           {"psnr_db", psnr_db},
          {"psnr", psnr_text(e.psnr_db)},               {"reference_noise_rms", e.reference_noise_rms}};
}

}  // namespace lucent
