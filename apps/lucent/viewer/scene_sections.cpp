// scene_sections.cpp: camera, lights, materials, method and render editors of the viewer panel.
#include "viewer/scene_sections.h"

#include <algorithm>
#include <map>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <imgui.h>

#include "lucent/material.h"
#include "methods/method_info.h"
#include "viewer/direction_widget.h"
#include "viewer/material_artist.h"
#include "viewer/param_widgets.h"

namespace lucent::viewer {
namespace {

// A light's RGB as a colour (max component 1) times an intensity, for a colour picker and a scalar.
bool colour_and_intensity(const char* label, glm::vec3& rgb, const char* intensity_label, float speed) {
  float intensity = std::max({rgb.r, rgb.g, rgb.b});
  glm::vec3 colour = intensity > 0.0f ? rgb / intensity : glm::vec3(1.0f);
  bool changed = ImGui::ColorEdit3(label, &colour.x, ImGuiColorEditFlags_Float);
  changed |= ImGui::DragFloat(intensity_label, &intensity, speed, 0.0f, 1e9f, "%.4g", ImGuiSliderFlags_Logarithmic);
  if (changed) rgb = colour * std::max(intensity, 0.0f);
  return changed;
}

bool directional_light(DirectionalLight& light, const Camera& view) {
  bool changed = direction_sphere("##sphere", light.direction, view, 110.0f);
  glm::vec2 angles = azimuth_elevation_deg(light.direction);
  if (ImGui::DragFloat2("azimuth, elevation [deg]", &angles.x, 0.5f, -180.0f, 180.0f, "%.1f")) {
    angles.y = std::clamp(angles.y, -90.0f, 90.0f);
    light.direction = travel_from_azimuth_elevation(angles);
    changed = true;
  }
  ImGui::TextDisabled("travels along [%.3f, %.3f, %.3f]", light.direction.x, light.direction.y, light.direction.z);
  const ParamDecl* radiance = find_scene_param("lights[]", "radiance");
  std::string unit = radiance ? fmt::format("radiance [{}]", radiance->unit) : "radiance";
  changed |= colour_and_intensity("colour", light.radiance, unit.c_str(), 0.02f);
  return changed;
}

bool point_light(PointLight& light, const Camera& view) {
  bool changed = scene_vec3("lights[]", "position", light.position);
  const ParamDecl* intensity = find_scene_param("lights[]", "intensity");
  std::string unit = intensity ? fmt::format("intensity [{}]", intensity->unit) : "intensity";
  changed |= colour_and_intensity("colour", light.intensity, unit.c_str(), 1e-4f);
  if (light.spot) {
    changed |= direction_sphere("##spot", light.direction, view, 90.0f);
    changed |= scene_float("lights[]", "inner_deg", light.inner_deg, 0.2f);
    changed |= scene_float("lights[]", "outer_deg", light.outer_deg, 0.2f);
    light.inner_deg = std::min(light.inner_deg, light.outer_deg);
  }
  return changed;
}

// Surface albedo and mean free path per band, as scene files and `lucent materials invert` give them: dragging
// either re-derives sigma_a and sigma_s by the model's inversion (g and eta as they are). A value the model cannot
// reach leaves the coefficients and shows why, until the next edit.
bool artist_editor(Material& m) {
  static std::map<ImGuiID, std::string> errors;  // by widget, the last refusal
  const ImGuiID id = ImGui::GetID("artist");
  const std::optional<ArtistParameters> artist = artist_parameters_of(m);
  if (!artist) {
    ImGui::TextDisabled("albedo, mfp: need sigma_a > 0 in every band");
    return false;
  }
  ArtistParameters edited = *artist;
  bool changed = ImGui::DragFloat3("albedo (surface)", &edited.albedo.x, 0.002f, 0.001f, 0.999f, "%.3f");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the flat, thick slab's total diffuse reflectance per band under this model (docs/materials.md)");
  changed |= ImGui::DragFloat3("mfp [mm]", &edited.mfp_mm.x, 0.01f, 1e-4f, 1e4f, "%.4g", ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("mean free path 1 / (sigma_a + sigma_s) per band [mm]");
  if (changed) errors[id] = apply_artist_parameters(m, edited);
  if (const auto it = errors.find(id); it != errors.end() && !it->second.empty())
    ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1.0f), "%s", it->second.c_str());
  return changed && errors[id].empty();
}

bool material_editor(Material& m) {
  bool changed = false;
  if (ImGui::BeginCombo("preset", m.name.c_str())) {
    for (const MaterialPreset& preset : material_presets()) {
      if (ImGui::Selectable(preset.name, m.name == preset.name)) {
        BssrdfModel model = m.model;
        MediumField field = m.field;
        const float thickness_mm = m.thickness_mm;  // the part's, not the medium's: kept like the model
        m = material_from_preset(preset);
        m.model = model;
        m.field = field;
        m.thickness_mm = thickness_mm;
        changed = true;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s%s%s", preset.source, *preset.note ? "\n" : "", preset.note);
    }
    ImGui::EndCombo();
  }
  // A textured material's coefficients, g, eta and model are what its maps' texels were inverted with: they are
  // shown, not edited (the scene file changes them; a preset above replaces the textured material).
  const bool textured = m.textured();
  if (textured) {
    ImGui::TextDisabled("textured: %s%s%s", m.maps->albedo_file.empty() ? "" : "albedo_map",
                        !m.maps->albedo_file.empty() && !m.maps->mfp_file.empty() ? ", " : "",
                        m.maps->mfp_file.empty() ? "" : "mfp_map");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("the maps' mean is shown; edit the material in the scene file (its texels are made at load)");
    ImGui::BeginDisabled();
  }
  bool coefficients = scene_vec3("objects[].material", "sigma_a", m.sigma_a, 1e-3f);
  coefficients |= scene_vec3("objects[].material", "sigma_s", m.sigma_s, 1e-2f);
  coefficients |= scene_vec3("objects[].material", "g", m.g, 1e-3f);
  if (!textured) {
    m.sigma_a = glm::max(m.sigma_a, glm::vec3(0.0f));
    m.sigma_s = glm::max(m.sigma_s, glm::vec3(0.0f));
    m.g = glm::clamp(m.g, glm::vec3(-0.99f), glm::vec3(0.99f));
  }
  if (!textured) coefficients |= artist_editor(m);
  if (coefficients) m.name = "custom";
  changed |= coefficients;
  changed |= scene_float("objects[].material", "eta", m.eta, 0.002f);
  const ParamDecl* model = find_scene_param("objects[].material", "model");
  if (model) {
    ParamValues values;
    values.set("model", std::string(to_string(m.model)));
    if (param_widget(*model, values)) {
      m.model = parse_bssrdf_model(values.text("model")).value_or(m.model);
      changed = true;
    }
  }
  if (m.model == BssrdfModel::Multipole && scene_float("objects[].material", "thickness_mm", m.thickness_mm, 0.01f)) {
    m.thickness_mm = std::max(m.thickness_mm, 0.0f);
    changed = true;
  }
  if (textured) ImGui::EndDisabled();
  // Heterogeneous medium (voxel-paths and volpath; the diffusion models ignore it): the field's type, feature size
  // and contrast from the same declarations as the scene parser; a volume keeps the file it was loaded from.
  if (const ParamDecl* type = find_scene_param("objects[].material.field", "type")) {
    ParamValues values;
    values.set("type", std::string(to_string(m.field.type)));
    if (param_widget(*type, values)) {
      const std::string& name = values.text("type");
      MediumFieldType next = name == "marble"    ? MediumFieldType::Marble
                             : name == "layered" ? MediumFieldType::Layered
                             : name == "volume" || name == "vdb" ? MediumFieldType::Volume  // a vdb is a volume once read
                                                 : MediumFieldType::None;
      if (next != MediumFieldType::Volume || m.field.volume) {
        m.field.type = next;
        changed = true;
      }
    }
    if (m.field.type == MediumFieldType::Marble || m.field.type == MediumFieldType::Layered) {
      changed |= scene_float("objects[].material.field", "scale_mm", m.field.scale_mm, 0.05f);
      changed |= scene_float("objects[].material.field", "contrast", m.field.contrast, 0.02f);
    } else if (m.field.volume) {
      ImGui::TextDisabled("volume %s (%dx%dx%d, m up to %.3g)", m.field.volume->source.c_str(), m.field.volume->size.x,
                          m.field.volume->size.y, m.field.volume->size.z, static_cast<double>(m.field.volume->max_value));
    }
  }
  glm::vec3 sigma_s_prime = m.sigma_s_prime();
  glm::vec3 albedo = sigma_s_prime / glm::max(m.sigma_a + sigma_s_prime, glm::vec3(1e-12f));
  ImGui::TextDisabled("sigma_s' [%.3g %.3g %.3g] mm^-1, albedo' [%.3f %.3f %.3f]", sigma_s_prime.x, sigma_s_prime.y,
                      sigma_s_prime.z, albedo.x, albedo.y, albedo.z);
  return changed;
}

}  // namespace

void camera_section(ViewerSession& session) {
  OrbitCamera& camera = session.camera();
  float fov = camera.camera().fov_y_deg;
  if (scene_float("camera", "fov_y_deg", fov, 0.2f)) camera.set_fov(fov);
  if (ImGui::Button("reset camera (R)")) camera.reset();
  ImGui::SameLine();
  std::string readout = camera_readout(camera.camera());
  if (ImGui::Button("copy")) ImGui::SetClipboardText(readout.c_str());
  ImGui::SameLine();
  ImGui::TextDisabled("distance %.3g", camera.distance());
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(readout.c_str());
  ImGui::PopTextWrapPos();
}

void lights_section(ViewerSession& session) {
  Scene& scene = session.edit();
  const Camera& view = session.camera().camera();
  bool changed = false;
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    DirectionalLight& light = scene.lights[i];
    if (!light.specular) continue;  // sampled from the environment map
    ImGui::PushID(static_cast<int>(i));
    if (ImGui::TreeNodeEx("light", ImGuiTreeNodeFlags_DefaultOpen, "directional light %zu", i)) {
      changed |= directional_light(light, view);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  for (std::size_t i = 0; i < scene.point_lights.size(); ++i) {
    PointLight& light = scene.point_lights[i];
    ImGui::PushID(static_cast<int>(1000 + i));
    if (ImGui::TreeNodeEx("light", ImGuiTreeNodeFlags_DefaultOpen, "%s light %zu", light.spot ? "spot" : "point", i)) {
      changed |= point_light(light, view);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  if (scene.environment)
    ImGui::TextDisabled("environment %s: %d lights", scene.environment->file.c_str(), scene.environment->light_count);
  if (changed) session.edited();
}

void materials_section(ViewerSession& session) {
  Scene& scene = session.edit();
  bool changed = false;
  float scale = scene.scale_mm;
  if (scene_float("scene", "scale_mm", scale, 0.05f)) scene.scale_mm = std::max(scale, 1e-6f), changed = true;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    SceneObject& object = scene.objects[i];
    ImGui::PushID(static_cast<int>(i));
    std::string title = fmt::format("{} ({})", object.name, object.material ? object.material->name : "opaque");
    if (ImGui::TreeNodeEx("object", object.material ? ImGuiTreeNodeFlags_DefaultOpen : 0, "%s", title.c_str())) {
      if (object.material) changed |= material_editor(*object.material);
      else changed |= scene_vec3("objects[]", "albedo", object.albedo, 0.005f);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  if (changed) session.edited();
}

void method_section(ViewerSession& session) {
  Scene& scene = session.edit();
  if (ImGui::BeginCombo("method", scene.method.c_str())) {
    std::string chosen;
    for (const methods::MethodInfo* method : methods::method_registry()) {
      if (ImGui::Selectable(std::string(method->name).c_str(), method->name == scene.method)) chosen = method->name;
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(method->summary).c_str());
    }
    ImGui::EndCombo();
    if (!chosen.empty()) session.set_method(chosen);
  }
  for (const ParamSection& section : scene_param_sections())
    if (section.name == scene.method && param_section_widgets(section, scene.method_params)) session.edited();
}

void render_section(ViewerSession& session) {
  Scene& scene = session.edit();
  bool changed = scene_float("render", "exposure", scene.render.exposure, 0.05f);
  const ParamDecl* tonemap = find_scene_param("render", "tonemap");
  if (tonemap) {
    static const char* kNames[] = {"linear", "reinhard", "aces"};  // ToneMapOperator order
    ParamValues values;
    values.set("tonemap", std::string(kNames[static_cast<int>(scene.render.tonemap)]));
    if (param_widget(*tonemap, values)) {
      for (int i = 0; i < 3; ++i)
        if (values.text("tonemap") == kNames[i]) scene.render.tonemap = static_cast<ToneMapOperator>(i);
      changed = true;
    }
  }
  changed |= scene_vec3("render", "background", scene.render.background, 0.005f);
  int seed = static_cast<int>(std::min<std::uint64_t>(scene.render.seed, 1u << 30));
  if (ImGui::DragInt("seed", &seed, 1.0f, 0, 1 << 30)) scene.render.seed = static_cast<unsigned>(std::max(seed, 0)), changed = true;
  // The denoising stage after the method (key D toggles it): its declared parameters.
  if (scene.denoise.has("enabled"))
    for (const ParamSection& section : scene_param_sections())
      if (section.name == "denoise" && ImGui::TreeNode("denoise")) {
        changed |= param_section_widgets(section, scene.denoise);
        ImGui::TreePop();
      }
  if (changed) session.edited();
}

}  // namespace lucent::viewer
