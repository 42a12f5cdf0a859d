// direction_widget.cpp: the light-direction sphere (ImGui draw list) and azimuth/elevation conversions.
#include "viewer/direction_widget.h"

#include <algorithm>
#include <cmath>

#include <imgui.h>

namespace lucent::viewer {
namespace {

struct ViewBasis {
  glm::vec3 right, up, back;  // back points from the scene towards the camera
};

ViewBasis basis_of(const Camera& view) {
  glm::vec3 back = glm::normalize(view.eye - view.target);
  glm::vec3 right = glm::normalize(glm::cross(view.up, back));
  return {right, glm::cross(back, right), back};
}

}  // namespace

glm::vec2 azimuth_elevation_deg(glm::vec3 travel) {
  glm::vec3 from = -glm::normalize(travel);
  return glm::degrees(glm::vec2(std::atan2(from.x, from.z), std::asin(std::clamp(from.y, -1.0f, 1.0f))));
}

glm::vec3 travel_from_azimuth_elevation(glm::vec2 degrees) {
  glm::vec2 r = glm::radians(degrees);
  glm::vec3 from(std::cos(r.y) * std::sin(r.x), std::sin(r.y), std::cos(r.y) * std::cos(r.x));
  return -from;
}

bool direction_sphere(const char* id, glm::vec3& travel, const Camera& view, float diameter) {
  ViewBasis b = basis_of(view);
  glm::vec3 from = -glm::normalize(travel);
  glm::vec3 local(glm::dot(from, b.right), glm::dot(from, b.up), glm::dot(from, b.back));

  ImVec2 corner = ImGui::GetCursorScreenPos();
  float radius = 0.5f * diameter;
  ImVec2 center(corner.x + radius, corner.y + radius);
  ImGui::InvisibleButton(id, ImVec2(diameter, diameter), ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  bool changed = false;
  // Drag: the point under the mouse on the visible hemisphere (or the hidden one, keeping its side).
  if (ImGui::IsItemActive() && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
    ImVec2 mouse = ImGui::GetIO().MousePos;
    glm::vec2 p((mouse.x - center.x) / radius, (center.y - mouse.y) / radius);
    if (glm::length(p) > 1.0f) p = glm::normalize(p);
    float z = std::sqrt(std::max(0.0f, 1.0f - glm::dot(p, p))) * (local.z < 0.0f ? -1.0f : 1.0f);
    local = glm::vec3(p, z);
    changed = true;
  }
  if (ImGui::IsItemClicked(ImGuiMouseButton_Right)) local.z = -local.z, changed = true;
  if (changed) {
    from = glm::normalize(local.x * b.right + local.y * b.up + local.z * b.back);
    travel = -from;
  }
  // Draw: the disk, its equator and meridian, the point.
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddCircleFilled(center, radius, IM_COL32(45, 48, 56, 255), 48);
  draw->AddCircle(center, radius, IM_COL32(140, 140, 150, 255), 48);
  draw->AddLine(ImVec2(center.x - radius, center.y), ImVec2(center.x + radius, center.y), IM_COL32(80, 80, 90, 255));
  draw->AddLine(ImVec2(center.x, center.y - radius), ImVec2(center.x, center.y + radius), IM_COL32(80, 80, 90, 255));
  ImVec2 dot(center.x + local.x * radius, center.y - local.y * radius);
  if (local.z >= 0.0f) draw->AddCircleFilled(dot, 5.0f, IM_COL32(255, 220, 120, 255));
  else draw->AddCircle(dot, 5.0f, IM_COL32(255, 220, 120, 255), 16, 2.0f);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("where the light comes from, as seen by the camera\ndrag: move; right-click: %s the objects",
                      local.z >= 0.0f ? "behind" : "in front of");
  return changed;
}

}  // namespace lucent::viewer
