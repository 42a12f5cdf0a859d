// image_error_json.h: an ImageError as JSON, the fields `lucent compare --json` prints and lucent.compare()
// returns.
#pragma once
#include <nlohmann/json.hpp>

#include "image/image_metrics.h"

namespace lucent {

nlohmann::json to_json(const ImageError& e);

}  // namespace lucent
