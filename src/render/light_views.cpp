// light_views.cpp: see light_views.h.
#include "render/light_views.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "lucent/error.h"

namespace lucent::render {
namespace {

using shader::LightGPU;
using shader::ViewGPU;

glm::vec3 any_perpendicular_up(glm::vec3 d) {
  return std::abs(d.y) > 0.99f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

ViewGPU perspective(glm::vec3 eye, glm::vec3 forward, glm::vec3 up, float half_angle, float z_near, float z_far,
                    int size) {
  ViewGPU v{};
  v.clip_from_world = glm::perspective(2.0f * half_angle, 1.0f, z_near, z_far) * glm::lookAt(eye, eye + forward, up);
  v.direction = glm::vec4(forward, 0.0f);
  v.radiance = glm::vec4(0.0f, 0.0f, 0.0f, 2.0f * half_angle / static_cast<float>(size));  // texel angle
  return v;
}

}  // namespace

ViewGPU orthographic_view(glm::vec3 center, glm::vec3 toward_eye, float half_width, float eye_distance,
                          float depth_range) {
  glm::vec3 eye = center + toward_eye * eye_distance;
  glm::mat4 view = glm::lookAt(eye, center, any_perpendicular_up(toward_eye));
  ViewGPU v{};
  v.clip_from_world = glm::ortho(-half_width, half_width, -half_width, half_width, 0.0f, depth_range) * view;
  v.direction = glm::vec4(-toward_eye, 2.0f * half_width);
  v.radiance = glm::vec4(0.0f, 0.0f, 0.0f, depth_range);
  return v;
}

void append_cube_views(std::vector<ViewGPU>& views, glm::vec3 eye, float z_near, float z_far, int size) {
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (glm::vec3 axis : axes)
    views.push_back(perspective(eye, axis, any_perpendicular_up(axis), 0.25f * 3.14159265f, z_near, z_far, size));
}

LightViews build_light_views(const Scene& scene, BoundingSphere translucent, BoundingSphere all, int light_map_size) {
  LightViews out;
  std::size_t count = scene.lights.size() + scene.point_lights.size();
  if (count > LUCENT_MAX_LIGHTS)
    throw Error(fmt::format("{}: {} lights; at most {} are supported", scene.source, count, LUCENT_MAX_LIGHTS));
  float half_width = 1.02f * translucent.radius + 1e-6f;
  float scene_half_width = 1.02f * all.radius + 1e-6f;
  for (const DirectionalLight& light : scene.lights) {
    LightGPU g{};
    g.position = glm::vec4(light.direction, static_cast<float>(LUCENT_LIGHT_DIRECTIONAL));
    g.power = glm::vec4(light.radiance, 0.0f);
    g.axis = glm::vec4(0.0f, 0.0f, 0.0f, light.specular ? 1.0f : 0.0f);
    // Object view: covers the translucent objects; depth covers the whole scene so occluders cast shadows.
    float eye_distance = glm::length(all.center - translucent.center) + all.radius + half_width;
    g.views = glm::ivec4(static_cast<int>(out.views.size()), 1, static_cast<int>(out.views.size()) + 1, 1);
    out.views.push_back(orthographic_view(translucent.center, -light.direction, half_width, eye_distance, 2.0f * eye_distance));
    out.views.push_back(orthographic_view(all.center, -light.direction, scene_half_width, scene_half_width, 2.0f * scene_half_width));
    out.lights.push_back(g);
  }
  for (const PointLight& light : scene.point_lights) {
    LightGPU g{};
    g.position = glm::vec4(light.position, static_cast<float>(light.spot ? LUCENT_LIGHT_SPOT : LUCENT_LIGHT_POINT));
    g.power = glm::vec4(intensity_in_scene_units(light, scene.scale_mm),
                        std::cos(glm::radians(light.inner_deg)));
    g.axis = glm::vec4(light.direction, std::cos(glm::radians(light.outer_deg)));
    float reach = glm::length(light.position - all.center) + all.radius;
    float z_near = 1e-3f * std::max(all.radius, 1e-6f);
    int first = static_cast<int>(out.views.size());
    float distance = glm::length(translucent.center - light.position);
    if (distance > 1.05f * half_width) {
      // Outside: one frustum framing the translucent objects, then the scene-wide shadow cube.
      glm::vec3 forward = (translucent.center - light.position) / distance;
      float half_angle = std::asin(std::min(1.0f, half_width / distance));
      // The near plane stays at the light: occluders between it and the objects must be in the G-buffer.
      out.views.push_back(perspective(light.position, forward, any_perpendicular_up(forward), half_angle, z_near,
                                      reach, light_map_size));
      g.views = glm::ivec4(first, 1, first + 1, 6);
    } else {
      g.views = glm::ivec4(first, 6, first, 6);  // inside: the cube map serves both
    }
    append_cube_views(out.views, light.position, z_near, reach, light_map_size);
    out.lights.push_back(g);
  }
  if (out.views.size() > LUCENT_MAX_LIGHT_VIEWS)
    throw Error(fmt::format("{}: the lights need {} light G-buffer layers; at most {} are supported (a directional "
                            "light needs 2, a point or spot light 6 or 7)",
                            scene.source, out.views.size(), LUCENT_MAX_LIGHT_VIEWS));
  return out;
}

}  // namespace lucent::render
