// param_widgets.cpp: ParamDecl -> ImGui slider, drag, checkbox, combo or text field.
#include "viewer/param_widgets.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "lucent/scene.h"

namespace lucent::viewer {
namespace {

constexpr double kUnbounded = 1e29;  // declarations use +-1e30 for "no bound"
constexpr int kSliderMaxSpan = 4096;  // integer ranges wider than this get a drag field instead of a slider

bool bounded(const ParamDecl& d) { return d.min > -kUnbounded && d.max < kUnbounded; }

std::string range_text(const ParamDecl& d) {
  if (d.type == ParamType::Enum) return fmt::format("one of {{{}}}", d.choices);
  if (d.type == ParamType::Bool || d.type == ParamType::String) return "";
  std::string lo = d.min <= -kUnbounded ? "-inf" : fmt::format("{:g}", d.min);
  std::string hi = d.max >= kUnbounded ? "inf" : fmt::format("{:g}", d.max);
  return fmt::format("range [{}, {}]{}{}", lo, hi, d.unit.empty() ? "" : " ", d.unit);
}

void tooltip(const ParamDecl& d) {
  if (!ImGui::IsItemHovered()) return;
  ImGui::BeginTooltip();
  ImGui::TextUnformatted(std::string(d.doc).c_str());
  std::string range = range_text(d);
  if (!range.empty()) ImGui::TextDisabled("%s", range.c_str());
  if (!d.default_json.empty()) ImGui::TextDisabled("default %s", std::string(d.default_json).c_str());
  ImGui::TextDisabled("%s", d.update == ParamUpdate::Live ? "live: taken by the next frame"
                                                          : "rebuild: a change recreates the method");
  ImGui::EndTooltip();
}

std::vector<std::string> split_choices(std::string_view choices) {
  std::vector<std::string> out;
  while (true) {
    auto bar = choices.find('|');
    out.emplace_back(choices.substr(0, bar));
    if (bar == std::string_view::npos) return out;
    choices.remove_prefix(bar + 1);
  }
}

// Drag speed: about 1/200 of the range, or 1% of the value for unbounded ones.
float drag_speed(const ParamDecl& d, double value) {
  if (bounded(d)) return static_cast<float>(std::max((d.max - d.min) / 200.0, 1e-4));
  return static_cast<float>(std::max(std::abs(value) * 0.01, 1e-3));
}

bool number_widget(const ParamDecl& d, const std::string& label, ParamValues& values) {
  double value = values.number(d.name);
  float lo = static_cast<float>(std::max(d.min, -1e9)), hi = static_cast<float>(std::min(d.max, 1e9));
  bool changed = false;
  if (d.type == ParamType::Int) {
    int v = static_cast<int>(value);
    bool slider = bounded(d) && d.max - d.min <= kSliderMaxSpan;
    changed = slider ? ImGui::SliderInt(label.c_str(), &v, static_cast<int>(d.min), static_cast<int>(d.max), "%d",
                                        ImGuiSliderFlags_AlwaysClamp)
                     : ImGui::DragInt(label.c_str(), &v, 1.0f, static_cast<int>(std::max(d.min, -2e9)),
                                      static_cast<int>(std::min(d.max, 2e9)), "%d", ImGuiSliderFlags_AlwaysClamp);
    if (changed) values.set(d.name, static_cast<double>(v));
  } else {
    float v = static_cast<float>(value);
    changed = ImGui::DragFloat(label.c_str(), &v, drag_speed(d, value), lo, hi, "%.4g", ImGuiSliderFlags_AlwaysClamp);
    if (changed) values.set(d.name, std::clamp(static_cast<double>(v), d.min, d.max));
  }
  return changed;
}

bool vector_widget(const ParamDecl& d, const std::string& label, ParamValues& values) {
  glm::vec3 v = values.vec3(d.name);
  float lo = static_cast<float>(std::max(d.min, -1e9)), hi = static_cast<float>(std::min(d.max, 1e9));
  float speed = drag_speed(d, glm::length(v));
  bool changed = d.type == ParamType::Vec2
                     ? ImGui::DragFloat2(label.c_str(), &v.x, speed, lo, hi, "%.4g", ImGuiSliderFlags_AlwaysClamp)
                     : ImGui::DragFloat3(label.c_str(), &v.x, speed, lo, hi, "%.4g", ImGuiSliderFlags_AlwaysClamp);
  if (changed) values.set(d.name, v);
  return changed;
}

bool enum_widget(const ParamDecl& d, const std::string& label, ParamValues& values) {
  const std::string current = values.text(d.name);
  bool changed = false;
  if (ImGui::BeginCombo(label.c_str(), current.c_str())) {
    for (const std::string& choice : split_choices(d.choices)) {
      if (ImGui::Selectable(choice.empty() ? "(none)" : choice.c_str(), choice == current) && choice != current) {
        values.set(d.name, choice);
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  return changed;
}

}  // namespace

std::string param_label(const ParamDecl& decl) {
  return decl.unit.empty() ? std::string(decl.name) : fmt::format("{} [{}]", decl.name, decl.unit);
}

bool param_widget(const ParamDecl& d, ParamValues& values) {
  std::string label = param_label(d);
  if (!values.has(d.name)) {
    ImGui::TextDisabled("%s: (not set)", label.c_str());
    return false;
  }
  bool changed = false;
  switch (d.type) {
    case ParamType::Int:
    case ParamType::Float: changed = number_widget(d, label, values); break;
    case ParamType::Bool: {
      bool v = values.boolean(d.name);
      changed = ImGui::Checkbox(label.c_str(), &v);
      if (changed) values.set(d.name, v);
      break;
    }
    case ParamType::Enum: changed = enum_widget(d, label, values); break;
    case ParamType::String: {
      std::string v = values.text(d.name);
      changed = ImGui::InputText(label.c_str(), &v, ImGuiInputTextFlags_EnterReturnsTrue);
      if (changed) values.set(d.name, v);
      break;
    }
    case ParamType::Vec2:
    case ParamType::Vec3: changed = vector_widget(d, label, values); break;
    case ParamType::Vec3List:
      ImGui::TextWrapped("%s = %s", label.c_str(), to_string(values.all().at(std::string(d.name))).c_str());
      break;
  }
  tooltip(d);
  return changed;
}

bool param_section_widgets(const ParamSection& section, ParamValues& values) {
  bool changed = false;
  for (const ParamDecl& d : section.params) {
    ImGui::PushID(d.name.data(), d.name.data() + d.name.size());
    changed |= param_widget(d, values);
    ImGui::PopID();
  }
  return changed;
}

const ParamDecl* find_scene_param(std::string_view section, std::string_view name) {
  static const std::vector<ParamSection> sections = scene_param_sections();
  for (const ParamSection& s : sections)
    if (s.name == section)
      for (const ParamDecl& d : s.params)
        if (d.name == name) return &d;
  return nullptr;
}

bool scene_float(std::string_view section, std::string_view name, float& value, float speed) {
  const ParamDecl* d = find_scene_param(section, name);
  if (!d) return ImGui::DragFloat(std::string(name).c_str(), &value, speed);
  float lo = static_cast<float>(std::max(d->min, -1e9)), hi = static_cast<float>(std::min(d->max, 1e9));
  bool changed = ImGui::DragFloat(param_label(*d).c_str(), &value, speed, lo, hi, "%.4g", ImGuiSliderFlags_AlwaysClamp);
  tooltip(*d);
  return changed;
}

bool scene_vec3(std::string_view section, std::string_view name, glm::vec3& value, float speed) {
  const ParamDecl* d = find_scene_param(section, name);
  if (!d) return ImGui::DragFloat3(std::string(name).c_str(), &value.x, speed);
  float lo = static_cast<float>(std::max(d->min, -1e9)), hi = static_cast<float>(std::min(d->max, 1e9));
  bool changed = ImGui::DragFloat3(param_label(*d).c_str(), &value.x, speed, lo, hi, "%.4g", ImGuiSliderFlags_AlwaysClamp);
  tooltip(*d);
  return changed;
}

}  // namespace lucent::viewer
