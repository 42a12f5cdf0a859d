// light_views.h: the lights of a scene as the GPU sees them (LightGPU) and the views of the layered light
// G-buffer (step 1 of Dal Corso et al. 2015, extended to point lights in their Section 3.3):
// - directional light: an orthographic view framing the translucent objects and one framing the whole scene
//   (shadows of opaque objects);
// - point or spot light outside the translucent objects' bounding sphere: one perspective frustum framing them,
//   plus a cube map (6 perspective faces) of the whole scene for shadows;
// - point or spot light inside it (a candle, a lamp shade): one cube map serves both.
#pragma once
#include <vector>

#include "lucent/scene.h"
#include "render/scene_gpu.h"
#include "shared/shader_io.h"

namespace lucent::render {

struct LightViews {
  std::vector<shader::LightGPU> lights;  // directional lights first, then point and spot lights
  std::vector<shader::ViewGPU> views;    // light G-buffer layers, indexed by LightGPU::views
};

// Throws lucent::Error naming the scene when the lights need more than LUCENT_MAX_LIGHTS lights or
// LUCENT_MAX_LIGHT_VIEWS layers.
LightViews build_light_views(const Scene& scene, BoundingSphere translucent, BoundingSphere all, int light_map_size);

// An orthographic view looking along -toward_eye at a sphere (center, half_width), eye at eye_distance from
// the centre, depth spanning [0, depth_range]: direction = (-toward_eye, view width), radiance.w = depth range.
// Used for directional lights and for the scattered-radiosity maps.
shader::ViewGPU orthographic_view(glm::vec3 center, glm::vec3 toward_eye, float half_width, float eye_distance,
                                  float depth_range);

// Appends the 6 perspective faces +X -X +Y -Y +Z -Z of a cube map about `eye` (the order of cube_face() in
// shaders/common/frame.glsl).
void append_cube_views(std::vector<shader::ViewGPU>& views, glm::vec3 eye, float z_near, float z_far, int size);

}  // namespace lucent::render
