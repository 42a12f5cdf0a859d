// image_error_json.cpp: ImageError fields by name.
#include "image/image_error_json.h"

namespace lucent {

nlohmann::json to_json(const ImageError& e) {
  return {{"rmse", {e.rmse[0], e.rmse[1], e.rmse[2]}}, {"rmse_rgb", e.rmse_rgb},
          {"relative_mse", e.relative_mse},             {"mean_error", e.mean_error},
          {"mean_error_se", e.mean_error_se},           {"psnr_db", e.psnr_db},
          {"reference_noise_rms", e.reference_noise_rms}};
}

}  // namespace lucent
