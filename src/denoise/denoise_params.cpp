// denoise_params.cpp: the denoising stage's settings from the scene's values.
#include "denoise/denoise_params.h"

namespace lucent::denoise {

DenoiseSettings denoise_settings(const ParamValues& values) {
  DenoiseSettings s;
  if (values.has("enabled")) s.enabled = values.boolean("enabled");
  if (values.has("iterations")) s.iterations = values.integer("iterations");
  if (values.has("sigma_luminance")) s.sigma_luminance = static_cast<float>(values.number("sigma_luminance"));
  if (values.has("normal_power")) s.normal_power = static_cast<float>(values.number("normal_power"));
  if (values.has("sigma_plane")) s.sigma_plane = static_cast<float>(values.number("sigma_plane"));
  if (values.has("history_frames")) s.history_frames = values.integer("history_frames");
  if (values.has("fade_frames")) s.fade_frames = static_cast<float>(values.number("fade_frames"));
  return s;
}

}  // namespace lucent::denoise
