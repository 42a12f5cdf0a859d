// direction_widget.h: a light direction edited by dragging a point on a sphere drawn as seen by the camera
// (where the light comes from), with azimuth and elevation sliders in world space (y up) beside it.
#pragma once
#include <glm/glm.hpp>

#include "lucent/scene.h"

namespace lucent::viewer {

// `travel` is the unit direction the light travels (Scene convention). The disk shows the hemisphere facing the
// camera; the point is filled when the light is in front of the objects, hollow when behind them (right-click
// the disk to move it to the other side). True when changed.
bool direction_sphere(const char* id, glm::vec3& travel, const Camera& view, float diameter);

// Where the light comes from as azimuth (about +y from +z towards +x) and elevation, in degrees, and back.
glm::vec2 azimuth_elevation_deg(glm::vec3 travel);
glm::vec3 travel_from_azimuth_elevation(glm::vec2 degrees);

}  // namespace lucent::viewer
