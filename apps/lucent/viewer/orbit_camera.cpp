// orbit_camera.cpp: orbit, pan and zoom as rotations and translations of the look-at camera.
#include "viewer/orbit_camera.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

namespace lucent::viewer {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kMinPolarAngle = 0.01f;  // [radians] keeps the view direction off the up axis

glm::vec3 rotate(glm::vec3 v, glm::vec3 axis, float radians) {
  return glm::vec3(glm::rotate(glm::mat4(1.0f), radians, axis) * glm::vec4(v, 0.0f));
}

// Shortest text that reads back as the same float.
std::string shortest(float x) {
  for (int digits = 1; digits <= 9; ++digits) {
    std::string text = fmt::format("{:.{}g}", x, digits);
    if (std::strtof(text.c_str(), nullptr) == x) return text;
  }
  return fmt::format("{:.9g}", x);
}

std::string vector_text(glm::vec3 v) { return fmt::format("[{}, {}, {}]", shortest(v.x), shortest(v.y), shortest(v.z)); }

}  // namespace

void OrbitCamera::orbit(float dx_pixels, float dy_pixels) {
  constexpr float kRadiansPerPixel = kPi / 600.0f;
  glm::vec3 up = glm::normalize(camera_.up);
  glm::vec3 offset = camera_.eye - camera_.target;
  // Yaw about the up axis; pitch about the camera's right axis, clamped short of the poles.
  offset = rotate(offset, up, -dx_pixels * kRadiansPerPixel);
  float polar = std::acos(std::clamp(glm::dot(glm::normalize(offset), up), -1.0f, 1.0f));
  float pitch = std::clamp(-dy_pixels * kRadiansPerPixel, kMinPolarAngle - polar, kPi - kMinPolarAngle - polar);
  glm::vec3 right = glm::cross(up, offset);
  if (glm::length(right) > 1e-12f) offset = rotate(offset, glm::normalize(right), pitch);
  camera_.eye = camera_.target + offset;
}

void OrbitCamera::pan(float dx_pixels, float dy_pixels, float view_height) {
  glm::vec3 forward = glm::normalize(camera_.target - camera_.eye);
  glm::vec3 right = glm::normalize(glm::cross(forward, camera_.up));
  glm::vec3 up = glm::cross(right, forward);
  // Scene units per pixel at the target's depth.
  float units_per_pixel = 2.0f * distance() * std::tan(glm::radians(camera_.fov_y_deg) * 0.5f) / std::max(view_height, 1.0f);
  glm::vec3 shift = (-dx_pixels * right + dy_pixels * up) * units_per_pixel;
  camera_.eye += shift;
  camera_.target += shift;
}

void OrbitCamera::zoom(float wheel_steps) {
  glm::vec3 offset = camera_.eye - camera_.target;
  float factor = std::pow(0.9f, wheel_steps);
  camera_.eye = camera_.target + offset * std::max(factor, 1e-3f);
}

bool OrbitCamera::moved() const {
  return camera_.eye != home_.eye || camera_.target != home_.target || camera_.fov_y_deg != home_.fov_y_deg;
}

float OrbitCamera::distance() const { return glm::length(camera_.eye - camera_.target); }

std::string camera_readout(const Camera& camera) {
  return fmt::format("\"camera\": {{ \"eye\": {}, \"target\": {}, \"up\": {}, \"fov_y_deg\": {} }}",
                     vector_text(camera.eye), vector_text(camera.target), vector_text(camera.up),
                     shortest(camera.fov_y_deg));
}

}  // namespace lucent::viewer
