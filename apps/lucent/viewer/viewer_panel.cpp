// viewer_panel.cpp: the side panel's layout, status readouts and file actions.
#include "viewer/viewer_panel.h"

#include <filesystem>

#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "viewer/scene_sections.h"

namespace lucent::viewer {
namespace {

// Text wrapped at the panel's visible right edge (the panel scrolls sideways, so its content may be wider).
void wrapped_text(const std::string& text) {
  const ImGuiStyle& style = ImGui::GetStyle();
  ImGui::PushTextWrapPos(ImGui::GetScrollX() + ImGui::GetWindowWidth() - style.WindowPadding.x - style.ScrollbarSize);
  ImGui::TextUnformatted(text.c_str());
  ImGui::PopTextWrapPos();
}

void error_box(const std::string& error) {
  if (error.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
  wrapped_text(error);
  ImGui::PopStyleColor();
  ImGui::Separator();
}

void convergence_and_timings(ViewerSession& session, PanelState& state) {
  Renderer* renderer = session.renderer();
  if (!renderer) {
    ImGui::TextDisabled("no scene rendered (see the error above)");
    return;
  }
  const FrameTimings& t = renderer->timings();
  // What is on screen and what is being computed: on a software rasterizer a frame takes seconds, and the window
  // is redrawn only between frames.
  wrapped_text(state.frame_status);
  wrapped_text(fmt::format("{}x{} pixels rendered, {}", state.view_width, state.view_height, state.frame_rate));
  if (ImGui::Button("restart")) session.restart();
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90.0f);
  ImGui::DragInt("stop after (0: never)", &state.stop_after_frames, 1.0f, 0, 1000000, "%d frames");
  bool animated = false;
  for (const SceneObject& object : renderer->scene().objects) animated = animated || object.animated();
  if (animated) {
    // Deforming objects and blob surfaces: play with the wall clock, or scrub (each new time re-renders).
    ImGui::Checkbox("play", &state.playing);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120.0f);
    if (ImGui::DragFloat("time [s]", &state.time_seconds, 0.02f, 0.0f, 3600.0f, "%.2f")) state.playing = false;
  }
  if (t.total_ms > 0.0)
    ImGui::Text("GPU %.2f ms/frame (frame %llu), %.1f MiB", t.total_ms, static_cast<unsigned long long>(t.frame),
                static_cast<double>(t.gpu_memory_bytes) / (1024.0 * 1024.0));
  else
    ImGui::TextDisabled("GPU timings: after the first frames (read a few frames late)");
  // Passes and statistics as the method declares them, from the newest frame the GPU has reported (a few frames
  // behind: reading them never stalls the viewer).
  if (ImGui::TreeNode("GPU passes [ms]")) {
    if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
      for (const PassTiming& pass : t.passes) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(pass.name.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%8.3f", pass.ms);
      }
      ImGui::EndTable();
    }
    if (ImGui::BeginTable("stats", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
      for (const FrameStatistic& stat : t.stats) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(stat.name.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%.4g %s", stat.value, stat.unit.c_str());
      }
      ImGui::EndTable();
    }
    ImGui::TextDisabled("frame %llu; %s", static_cast<unsigned long long>(t.frame), renderer->device().c_str());
    ImGui::TreePop();
  }
}

void replace_extension(std::string& path, const char* extension) {
  path = std::filesystem::path(path).replace_extension(extension).string();
}

PanelActions files_section(ViewerSession& session, PanelState& state) {
  PanelActions actions;
  ImGui::InputText("##screenshot", &state.screenshot_path);
  ImGui::SameLine();
  if (ImGui::Button("PNG")) replace_extension(state.screenshot_path, ".png"), actions.screenshot = true;
  ImGui::SameLine();
  if (ImGui::Button("EXR")) replace_extension(state.screenshot_path, ".exr"), actions.screenshot = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("PNG: the tone-mapped view (P); EXR: linear radiance");
  ImGui::InputText("##scene", &state.scene_save_path);
  ImGui::SameLine();
  actions.save_scene = ImGui::Button("save scene as");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the scene with this camera, size and frame count: `lucent render` of it reproduces the view");
  if (!session.scene_path().empty()) {
    actions.reload = ImGui::Button("reload");
    ImGui::SameLine();
    bool watch = session.watching();
    if (ImGui::Checkbox("reload when the file changes", &watch)) session.set_watching(watch);
  }
  if (!state.status.empty()) ImGui::TextWrapped("%s", state.status.c_str());
  return actions;
}

}  // namespace

PanelActions draw_panel(ViewerSession& session, PanelState& state, float width, float height) {
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  // The panel is the window's height and scrolls (vertically, and sideways for a long label in a narrow panel).
  ImGui::Begin("lucent", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_HorizontalScrollbar);
  ImGui::PushItemWidth(ImGui::GetContentRegionAvail().x * 0.48f);  // the rest for labels with units
  ImGui::TextDisabled("%s", session.scene_path().empty() ? "<built-in default scene>" : session.scene_path().c_str());
  error_box(session.error());
  convergence_and_timings(session, state);
  PanelActions actions;
  if (ImGui::CollapsingHeader("Files", ImGuiTreeNodeFlags_DefaultOpen)) actions = files_section(session, state);
  if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) camera_section(session);
  if (ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) lights_section(session);
  if (ImGui::CollapsingHeader("Materials", ImGuiTreeNodeFlags_DefaultOpen)) materials_section(session);
  if (ImGui::CollapsingHeader("Method", ImGuiTreeNodeFlags_DefaultOpen)) method_section(session);
  if (ImGui::CollapsingHeader("Render")) render_section(session);
  if (ImGui::CollapsingHeader("Controls")) {
    ImGui::TextWrapped(
        "left drag: orbit\nright or middle drag, shift + left drag: pan\nwheel: zoom\nR: reset camera\n"
        "P: screenshot\nEsc: quit");
  }
  ImGui::PopItemWidth();
  ImGui::End();
  return actions;
}

}  // namespace lucent::viewer
