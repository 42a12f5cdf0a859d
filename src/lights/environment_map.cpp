// environment_map.cpp: loading and checking equirectangular environment maps, their exact power and
// irradiance (sums over all pixels, in double precision), and the texture the renderer uploads for the
// specular lookup. Mapping and pixel solid angles: lights/equirect.h.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "io/file_path_check.h"
#include "lights/equirect.h"
#include "lucent/environment.h"
#include "lucent/error.h"
#include "lucent/output_file.h"

namespace lucent {
namespace {

// The largest environment radiance accepted. The brightest skies captured with the sun in them reach about 1e9;
// 3e38 (float's limit) made the sums over a region of the map infinite (NaN pixels, `envmap lights` printing
// inf). 1e20 over the whole sphere stays far inside float.
constexpr float kMaxEnvironmentRadiance = 1e20f;

// Throws unless every channel is finite, non-negative and at most kMaxEnvironmentRadiance; names the first
// offending pixel.
void check_radiance(const EnvironmentMap& map) {
  constexpr const char* kChannelNames[3] = {"R", "G", "B"};
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const float value = map.at(x, y)[c];
        if (value >= 0.0f && value <= kMaxEnvironmentRadiance) continue;
        throw Error(fmt::format("{}: pixel ({}, {}) has {} = {}; environment radiance must be finite, non-negative "
                                "and at most {:g}",
                                map.source, x, y, kChannelNames[c], value, kMaxEnvironmentRadiance));
      }
}

// Solid angle of one pixel in each row (the shared formula, which keeps float precision at the poles).
std::vector<double> row_solid_angles(int width, int height) {
  std::vector<double> solid_angle(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y)
    solid_angle[static_cast<std::size_t>(y)] = shader::equirect_pixel_solid_angle(y, width, height);
  return solid_angle;
}

// Weights of source cells [0, n_source) averaged into n_target equal cells: for target cell t, the covered
// source cells and their overlap fractions (summing to 1).
struct Footprint {
  int first = 0;
  std::vector<double> weights;
};
std::vector<Footprint> box_footprints(int n_source, int n_target) {
  std::vector<Footprint> footprints(static_cast<std::size_t>(n_target));
  const double scale = static_cast<double>(n_source) / n_target;
  for (int t = 0; t < n_target; ++t) {
    const double begin = t * scale, end = (t + 1) * scale;
    Footprint& footprint = footprints[static_cast<std::size_t>(t)];
    footprint.first = static_cast<int>(std::floor(begin));
    for (int s = footprint.first; s < n_source && s < end; ++s) {
      const double overlap = std::min(end, s + 1.0) - std::max(begin, static_cast<double>(s));
      footprint.weights.push_back(overlap / scale);
    }
  }
  return footprints;
}

}  // namespace

EnvironmentMap environment_map_from_image(const ImageRGBA32F& image, const std::string& source) {
  if (image.width <= 0 || image.height <= 0 || image.width != 2 * image.height) {
    throw Error(fmt::format("{}: environment map is {}x{}; an equirectangular map must be twice as wide as high",
                            source, image.width, image.height));
  }
  EnvironmentMap map;
  map.source = source;
  map.width = image.width;
  map.height = image.height;
  map.radiance.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      const float* pixel = image.at(x, y);
      map.at(x, y) = glm::vec3(pixel[0], pixel[1], pixel[2]);
    }
  check_radiance(map);
  return map;
}

EnvironmentMap load_environment_map(const std::string& path) {
  check_file_path(path);
  const std::string extension = lowercase_extension(path);
  if (extension != ".hdr" && extension != ".exr") {
    throw Error(fmt::format("{}: an environment map must be a .hdr or .exr file", path));
  }
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw Error(fmt::format("{}: cannot read environment map: no such file", path));
  }
  return environment_map_from_image(extension == ".hdr" ? read_hdr(path) : read_exr(path), path);
}

ImageRGBA32F environment_map_to_image(const EnvironmentMap& map) {
  ImageRGBA32F image{map.width, map.height, {}};
  image.pixels.reserve(4 * map.radiance.size());
  for (const glm::vec3& L : map.radiance) image.pixels.insert(image.pixels.end(), {L.r, L.g, L.b, 1.0f});
  return image;
}

glm::vec3 environment_power(const EnvironmentMap& map) {
  const std::vector<double> solid_angle = row_solid_angles(map.width, map.height);
  glm::dvec3 power(0.0);
  for (int y = 0; y < map.height; ++y) {
    glm::dvec3 row(0.0);
    for (int x = 0; x < map.width; ++x) row += glm::dvec3(map.at(x, y));
    power += row * solid_angle[static_cast<std::size_t>(y)];
  }
  return glm::vec3(power);
}

std::vector<glm::vec3> environment_irradiance(const EnvironmentMap& map, const std::vector<glm::vec3>& normals) {
  // Pixels as (direction, L d_omega), skipping black ones.
  const std::vector<double> solid_angle = row_solid_angles(map.width, map.height);
  std::vector<glm::dvec3> directions, weighted_radiance;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      if (map.at(x, y) == glm::vec3(0.0f)) continue;
      directions.emplace_back(shader::equirect_pixel_direction(x, y, map.width, map.height));
      weighted_radiance.push_back(glm::dvec3(map.at(x, y)) * solid_angle[static_cast<std::size_t>(y)]);
    }
  std::vector<glm::vec3> irradiance;
  irradiance.reserve(normals.size());
  for (const glm::vec3& normal : normals) {
    const glm::dvec3 n(normal);
    glm::dvec3 E(0.0);
    for (std::size_t i = 0; i < directions.size(); ++i) {
      const double cosine = glm::dot(n, directions[i]);
      if (cosine > 0.0) E += cosine * weighted_radiance[i];
    }
    irradiance.emplace_back(E);
  }
  return irradiance;
}

glm::vec3 directional_lights_irradiance(const std::vector<DirectionalLight>& lights, glm::vec3 normal) {
  glm::vec3 E(0.0f);
  for (const DirectionalLight& light : lights) E += light.radiance * std::max(0.0f, -glm::dot(normal, light.direction));
  return E;
}

std::vector<glm::vec3> sphere_directions(int count) {
  std::vector<glm::vec3> directions;
  directions.reserve(static_cast<std::size_t>(std::max(count, 0)));
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / count;
    const double r = std::sqrt(std::max(0.0, 1.0 - y * y)), phi = golden_angle * i;
    directions.emplace_back(r * std::cos(phi), y, r * std::sin(phi));
  }
  return directions;
}

IrradianceError irradiance_error(const std::vector<glm::vec3>& normals, const std::vector<glm::vec3>& exact,
                                 const std::vector<DirectionalLight>& lights) {
  glm::dvec3 floor(0.0);
  for (const glm::vec3& E : exact) floor = glm::max(floor, 0.01 * glm::dvec3(E));
  IrradianceError error;
  double sum_squares = 0.0;
  for (std::size_t i = 0; i < normals.size() && i < exact.size(); ++i) {
    const glm::dvec3 approx(directional_lights_irradiance(lights, normals[i]));
    const glm::dvec3 reference(exact[i]);
    double relative = 0.0;
    for (int c = 0; c < 3; ++c) {
      if (floor[c] <= 0.0) continue;  // a channel the map does not light at all
      relative = std::max(relative, std::abs(approx[c] - reference[c]) / std::max(reference[c], floor[c]));
    }
    error.max_relative = std::max(error.max_relative, relative);
    sum_squares += relative * relative;
  }
  if (!normals.empty()) error.rms_relative = std::sqrt(sum_squares / static_cast<double>(normals.size()));
  return error;
}

EnvironmentTexture make_environment_texture(const EnvironmentMap& map, int max_width) {
  if (max_width < 2 || max_width % 2 != 0) {
    throw Error(fmt::format("environment texture: max_width {} must be an even number >= 2", max_width));
  }
  EnvironmentTexture texture;
  texture.width = std::min(map.width, max_width);
  texture.height = texture.width / 2;
  const std::vector<Footprint> columns = box_footprints(map.width, texture.width);
  const std::vector<Footprint> rows = box_footprints(map.height, texture.height);
  texture.rgb.reserve(3 * static_cast<std::size_t>(texture.width) * static_cast<std::size_t>(texture.height));
  for (const Footprint& row : rows)
    for (const Footprint& column : columns) {
      glm::dvec3 sum(0.0);
      for (std::size_t j = 0; j < row.weights.size(); ++j)
        for (std::size_t i = 0; i < column.weights.size(); ++i) {
          const int x = column.first + static_cast<int>(i), y = row.first + static_cast<int>(j);
          sum += row.weights[j] * column.weights[i] * glm::dvec3(map.at(x, y));
        }
      texture.rgb.insert(texture.rgb.end(),
                         {static_cast<float>(sum.r), static_cast<float>(sum.g), static_cast<float>(sum.b)});
    }
  texture.mean_radiance = environment_power(map) / (4.0f * shader::kPi);
  return texture;
}

}  // namespace lucent
