// synthetic_environment.cpp: procedural equirectangular maps (a clear sky with a sun, a smooth gradient, a
// constant) for the example scenes, the tests and the error measurements of docs/lights/environment.md.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include <fmt/format.h>

#include "lights/equirect.h"
#include "lucent/environment.h"
#include "lucent/error.h"

namespace lucent {
namespace {

EnvironmentMap blank_map(int width, const char* name) {
  if (width < 2 || width % 2 != 0)
    throw Error(fmt::format("{} environment: width {} must be even and >= 2", name, width));
  EnvironmentMap map;
  map.source = fmt::format("<{} environment {}x{}>", name, width, width / 2);
  map.width = width;
  map.height = width / 2;
  map.radiance.assign(static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height), glm::vec3(0.0f));
  return map;
}

// Sky radiance without the sun disc: a gradient from the horizon to the zenith, brighter around the sun,
// and the ground below the horizon.
glm::vec3 sky_radiance(const SkyDescription& sky, glm::vec3 w) {
  if (w.y < 0.0f) return sky.ground;
  const float elevation = std::sqrt(w.y);  // widens the bright band near the horizon
  const glm::vec3 gradient = glm::mix(sky.horizon, sky.zenith, elevation);
  const float cos_sun = glm::dot(w, sky.to_sun);
  const float glow = 0.6f * std::exp(8.0f * (cos_sun - 1.0f));  // circumsolar brightening, about 30 degrees wide
  return gradient * (1.0f + glow);
}

}  // namespace

EnvironmentMap make_sky_environment(const SkyDescription& sky) {
  EnvironmentMap map = blank_map(sky.width, "sky");
  const float cos_sun_radius = std::cos(glm::radians(sky.sun_radius_deg));
  constexpr int kSub = 4;  // kSub x kSub subsamples per pixel anti-alias the disc and the horizon
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      glm::vec3 sum(0.0f);
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i) {
          const glm::vec2 uv(
              (static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / kSub) / static_cast<float>(map.width),
              (static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / kSub) / static_cast<float>(map.height));
          const glm::vec3 w = shader::equirect_direction(uv);
          const bool in_sun = glm::dot(w, sky.to_sun) >= cos_sun_radius && w.y >= 0.0f;
          sum += in_sun ? sky.sun_radiance : sky_radiance(sky, w);
        }
      map.at(x, y) = sum / static_cast<float>(kSub * kSub);
    }
  return map;
}

EnvironmentMap make_gradient_environment(int width) {
  EnvironmentMap map = blank_map(width, "gradient");
  const glm::vec3 base(0.6f, 0.7f, 0.9f);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      const glm::vec3 w = shader::equirect_pixel_direction(x, y, map.width, map.height);
      map.at(x, y) = base * (1.0f + 0.6f * w.y + 0.3f * w.x);
    }
  return map;
}

EnvironmentMap make_constant_environment(int width, glm::vec3 radiance) {
  EnvironmentMap map = blank_map(width, "constant");
  std::fill(map.radiance.begin(), map.radiance.end(), radiance);
  return map;
}

}  // namespace lucent
