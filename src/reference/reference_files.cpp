// reference_files.cpp: see reference_files.h.
#include "reference/reference_files.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "lucent/error.h"
#include "io/input_file.h"
#include "lucent/output_file.h"
#include "params/param_json.h"

namespace lucent::reference {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string beside(const std::string& exr, const std::string& suffix) {
  const fs::path p(exr);
  return (p.parent_path() / (p.stem().string() + suffix)).string();
}

// The metadata object in `path`, nullopt when the file does not exist.
std::optional<json> read_json_object(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return std::nullopt;
  require_regular_file(path);
  std::ifstream in(path);
  if (!in) throw Error(fmt::format("{}: cannot open reference metadata", path));
  std::stringstream text;
  text << in.rdbuf();
  json j = parse_json(text.str(), JsonLocation{path, ""});
  if (!j.is_object()) throw Error(fmt::format("{}: malformed reference metadata (not a JSON object)", path));
  return j;
}

bool holds_sample_count(const json& j) {
  return j.contains("samples_per_pixel") && j["samples_per_pixel"].is_number_integer() &&
         j["samples_per_pixel"].get<long long>() > 0 &&
         j["samples_per_pixel"].get<long long>() <= std::numeric_limits<int>::max();
}

}  // namespace

ReferenceFiles reference_files(const std::string& mean_exr) {
  return {mean_exr, beside(mean_exr, ".stderr.exr"), beside(mean_exr, ".meta.json")};
}

void save_reference(const ReferenceFiles& files, const ReferenceImage& image, json metadata) {
  metadata["samples_per_pixel"] = image.samples_per_pixel;
  metadata["seconds"] = image.seconds;
  OutputSet set;
  auto encode = [](const std::string& path, const ImageRGBA32F& picture) {
    try {
      return encode_exr(picture);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}", path, e.what()));
    }
  };
  set.add(files.mean, encode(files.mean, image.mean));
  set.add(files.standard_error, encode(files.standard_error, image.standard_error));
  // Paths in the metadata may not be UTF-8 (file names are bytes): replaced, never an error after hours of work.
  set.add(files.metadata, metadata.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
  set.commit();
}

std::optional<json> read_reference_metadata(const ReferenceFiles& files) {
  if (std::optional<json> meta = read_json_object(files.metadata)) {
    if (!holds_sample_count(*meta))
      throw Error(fmt::format("{}: malformed reference metadata: no samples_per_pixel > 0", files.metadata));
    return meta;
  }
  // The name used before ".meta.json": only a file that is reference metadata, never a scene.
  const std::string legacy = beside(files.mean, ".json");
  std::optional<json> meta;
  try {
    meta = read_json_object(legacy);
  } catch (const Error&) {
    return std::nullopt;
  }
  if (meta && holds_sample_count(*meta) && meta->contains("integrator") && !meta->contains("objects")) return meta;
  return std::nullopt;
}

StoredReference load_reference(const ReferenceFiles& files) {
  std::optional<json> meta = read_reference_metadata(files);
  if (!meta) throw Error(fmt::format("{}: no such file (the metadata written beside the reference)", files.metadata));
  StoredReference stored;
  stored.image.mean = read_exr(files.mean);
  stored.image.standard_error = read_exr(files.standard_error);
  if (stored.image.mean.width != stored.image.standard_error.width ||
      stored.image.mean.height != stored.image.standard_error.height)
    throw Error(fmt::format("{}: is {}x{} but {} is {}x{}", files.standard_error, stored.image.standard_error.width,
                            stored.image.standard_error.height, files.mean, stored.image.mean.width,
                            stored.image.mean.height));
  // Every pixel a reference: a finite, non-negative mean and standard error in each colour band. Resuming,
  // merging or comparing against anything else would carry NaN on, or report a standard error of 0 as if exact.
  const int width = stored.image.mean.width;
  for (std::size_t k = 0; k < stored.image.mean.pixels.size(); ++k) {
    if (k % 4 == 3) continue;
    const float m = stored.image.mean.pixels[k], se = stored.image.standard_error.pixels[k];
    if (!(std::isfinite(m) && m >= 0.0f && std::isfinite(se) && se >= 0.0f)) {
      const std::size_t pixel = k / 4, w = static_cast<std::size_t>(std::max(1, width));
      throw Error(fmt::format("{}: pixel ({}, {}) {} has mean {} and standard error {}; a reference's are finite and "
                              ">= 0 (see {})",
                              files.mean, pixel % w, pixel / w, "rgb"[k % 4], m, se, files.standard_error));
    }
  }
  stored.image.samples_per_pixel = (*meta)["samples_per_pixel"].get<int>();
  const json seconds = meta->contains("seconds") ? (*meta)["seconds"] : json(0.0);
  stored.image.seconds = seconds.is_number() ? seconds.get<double>() : 0.0;
  stored.metadata = std::move(*meta);
  return stored;
}

}  // namespace lucent::reference
