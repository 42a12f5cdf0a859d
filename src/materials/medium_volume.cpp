// medium_volume.cpp: see lucent/medium_volume.h; the lookups of MediumVolume and MediumField (lucent/material.h).
#include "lucent/medium_volume.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/file_path_check.h"
#include "lucent/error.h"
#include "io/input_file.h"
#include "lucent/output_file.h"
#include "media/heterogeneous_field.h"
#include "params/param_json.h"

namespace lucent {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kMaxAxis = 1024;
constexpr std::size_t kMaxVoxels = std::size_t{1} << 27;

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw Error(fmt::format("{}: {}", path, problem));
}

std::size_t voxel_count(glm::ivec3 size) {
  return static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) * static_cast<std::size_t>(size.z);
}

glm::ivec3 read_size(const json& header, const std::string& path) {
  if (!header.contains("size")) fail(path, "missing key \"size\" ([nx, ny, nz])");
  const json& s = header["size"];
  if (!s.is_array() || s.size() != 3) fail(path, "size: must be [nx, ny, nz]");
  glm::ivec3 size;
  for (int a = 0; a < 3; ++a) {
    if (!s[a].is_number_integer() || s[a].get<long long>() < 1 || s[a].get<long long>() > kMaxAxis)
      fail(path, fmt::format("size[{}]: must be an integer in [1, {}]", a, kMaxAxis));
    size[a] = s[a].get<int>();
  }
  if (voxel_count(size) > kMaxVoxels) fail(path, fmt::format("size: {} voxels, at most {}", voxel_count(size), kMaxVoxels));
  return size;
}

}  // namespace

float MediumVolume::multiplier(glm::vec3 unit) const {
  const glm::vec3 u = shader::volume_grid_coordinate(unit, glm::vec3(0.0f), glm::vec3(1.0f), size);
  const glm::ivec3 c = shader::volume_corner(u, size);
  const glm::vec3 w = u - glm::vec3(c);
  auto at = [&](int x, int y, int z) {
    x = std::min(x, size.x - 1), y = std::min(y, size.y - 1), z = std::min(z, size.z - 1);
    return values[(static_cast<std::size_t>(z) * static_cast<std::size_t>(size.y) + static_cast<std::size_t>(y)) *
                      static_cast<std::size_t>(size.x) +
                  static_cast<std::size_t>(x)];
  };
  float x00 = glm::mix(at(c.x, c.y, c.z), at(c.x + 1, c.y, c.z), w.x);
  float x10 = glm::mix(at(c.x, c.y + 1, c.z), at(c.x + 1, c.y + 1, c.z), w.x);
  float x01 = glm::mix(at(c.x, c.y, c.z + 1), at(c.x + 1, c.y, c.z + 1), w.x);
  float x11 = glm::mix(at(c.x, c.y + 1, c.z + 1), at(c.x + 1, c.y + 1, c.z + 1), w.x);
  return glm::mix(glm::mix(x00, x10, w.y), glm::mix(x01, x11, w.y), w.z);
}

float MediumField::max_multiplier() const {
  switch (type) {
    case MediumFieldType::None: return 1.0f;
    case MediumFieldType::Marble:
    case MediumFieldType::Layered: return 1.0f + contrast;
    case MediumFieldType::Volume: return volume ? volume->max_value : 1.0f;
  }
  return 1.0f;
}

float MediumField::multiplier(glm::vec3 p, glm::vec3 lower, glm::vec3 upper, float scene_scale_mm) const {
  if (type == MediumFieldType::Volume)
    return volume ? volume->multiplier((p - lower) / glm::max(upper - lower, glm::vec3(1e-12f))) : 1.0f;
  return shader::field_multiplier(static_cast<int>(type), p, lower, upper, scale_mm / scene_scale_mm, contrast);
}

std::string_view to_string(MediumFieldType type) {
  switch (type) {
    case MediumFieldType::None: return "none";
    case MediumFieldType::Marble: return "marble";
    case MediumFieldType::Layered: return "layered";
    case MediumFieldType::Volume: return "volume";
  }
  return "unknown";
}

std::shared_ptr<const MediumVolume> load_medium_volume(const std::string& header_path) {
  check_file_path(header_path);
  require_regular_file(header_path);
  std::ifstream in(header_path);
  if (!in) fail(header_path, "cannot open the volume header");
  json header = parse_json(in, header_path);
  if (header.is_discarded() || !header.is_object()) fail(header_path, "not a JSON object (volume header)");
  for (const auto& [key, value] : header.items())
    if (key != "size" && key != "format" && key != "range" && key != "data")
      fail(header_path, fmt::format("unknown key \"{}\" (size, format, range, data)", key));
  auto volume = std::make_shared<MediumVolume>();
  volume->source = header_path;
  volume->size = read_size(header, header_path);
  if (header.contains("format") && !header["format"].is_string()) fail(header_path, "format: must be \"float32\" or \"uint8\"");
  const std::string format = header.value("format", std::string("float32"));
  if (format != "float32" && format != "uint8") fail(header_path, fmt::format("format: '{}' is not float32 or uint8", format));
  glm::vec2 range(0.0f, 1.0f);
  if (header.contains("range")) {
    if (format != "uint8") fail(header_path, "range: only for format uint8");
    const json& r = header["range"];
    if (!r.is_array() || r.size() != 2 || !r[0].is_number() || !r[1].is_number())
      fail(header_path, "range: must be [lo, hi]");
    range = {r[0].get<float>(), r[1].get<float>()};
    if (!(range.x >= 0.0f) || !(range.y >= range.x) || !std::isfinite(range.y))
      fail(header_path, "range: needs 0 <= lo <= hi, finite");
  }
  if (!header.contains("data") || !header["data"].is_string()) fail(header_path, "missing key \"data\" (the raw file)");
  if (const std::string problem = file_path_problem(header["data"].get<std::string>()); !problem.empty())
    fail(header_path, "data: " + problem);
  fs::path data = fs::path(header_path).parent_path() / header["data"].get<std::string>();
  volume->data_file = data.string();
  if (const std::string kind = non_regular_file_kind(data.string()); !kind.empty())
    fail(header_path, fmt::format("data: '{}' is {}, not a regular file", data.string(), kind));
  std::ifstream raw(data, std::ios::binary);
  if (!raw) fail(header_path, fmt::format("data: cannot open '{}'", data.string()));
  const std::size_t count = voxel_count(volume->size);
  const std::size_t bytes_per = format == "uint8" ? 1 : 4;
  std::error_code size_error;
  const std::uintmax_t file_bytes = fs::file_size(data, size_error);
  if (size_error || file_bytes != count * bytes_per)  // checked before reading: a wrong path may be a huge file
    fail(header_path, fmt::format("data: '{}' has {} bytes, size {}x{}x{} {} needs {}", data.string(),
                                  size_error ? 0 : file_bytes, volume->size.x, volume->size.y, volume->size.z, format,
                                  count * bytes_per));
  std::vector<char> bytes((std::istreambuf_iterator<char>(raw)), std::istreambuf_iterator<char>());
  if (bytes.size() != count * bytes_per) fail(header_path, fmt::format("data: could not read '{}'", data.string()));
  volume->values.resize(count);
  static_assert(std::endian::native == std::endian::little, "volume files are little-endian");
  for (std::size_t i = 0; i < count; ++i) {
    float v;
    if (bytes_per == 1) {
      v = range.x + (range.y - range.x) * static_cast<float>(static_cast<unsigned char>(bytes[i])) / 255.0f;
    } else {
      std::memcpy(&v, bytes.data() + 4 * i, 4);
    }
    if (!(v >= 0.0f && v <= kMaxDensityMultiplier))
      fail(header_path, fmt::format("data: value {} at voxel ({}, {}, {}) is outside [0, {:g}]: a density multiplier "
                                    "m is finite, >= 0 and at most {:g}",
                                    v, i % static_cast<std::size_t>(volume->size.x),
                                    i / static_cast<std::size_t>(volume->size.x) % static_cast<std::size_t>(volume->size.y),
                                    i / (static_cast<std::size_t>(volume->size.x) * static_cast<std::size_t>(volume->size.y)),
                                    kMaxDensityMultiplier, kMaxDensityMultiplier));
    volume->values[i] = v;
  }
  volume->max_value = *std::max_element(volume->values.begin(), volume->values.end());
  return volume;
}

void save_medium_volume(const MediumVolume& volume, const std::string& header_path) {
  if (volume.values.size() != voxel_count(volume.size)) fail(header_path, "volume values do not match its size");
  fs::path raw = fs::path(header_path);
  raw.replace_extension(".raw");
  OutputSet files;  // the header and its data, as one set
  files.add(raw.string(), std::string(reinterpret_cast<const char*>(volume.values.data()),
                                      volume.values.size() * sizeof(float)));
  files.add(header_path, json{{"size", {volume.size.x, volume.size.y, volume.size.z}},
                              {"format", "float32"},
                              {"data", raw.filename().string()}}
                                 .dump(2) +
                             "\n");
  files.commit();
}

}  // namespace lucent
