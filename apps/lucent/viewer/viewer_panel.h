// viewer_panel.h: the viewer's ImGui side panel: errors (in red), convergence, GPU timings, frame rate and
// memory, the scene editors (scene_sections.h), and files: screenshot, save scene as, reload.
#pragma once
#include <string>

#include "viewer/viewer_session.h"

namespace lucent::viewer {

// Panel state that is not part of the scene.
struct PanelState {
  std::string screenshot_path = "out/view.png";  // .png: tone-mapped; .exr: linear radiance
  std::string scene_save_path = "out/view.json";
  int stop_after_frames = 0;                     // 0: keep accumulating
  std::string status;                            // result of the last file action
  std::string frame_rate;                        // frames rendered per second, or seconds per frame (FrameClock)
  std::string frame_status;                      // "rendering frame 3 (...)" or "idle: ..." (frame_status_text)
  int view_width = 0, view_height = 0;           // pixels rendered
  bool playing = false;                          // animated scenes: time advances with the wall clock
  float time_seconds = 0.0f;                     // animation time shown (Renderer::set_time)
};

// What the user asked for this frame.
struct PanelActions {
  bool screenshot = false;
  bool save_scene = false;
  bool reload = false;
};

PanelActions draw_panel(ViewerSession& session, PanelState& state, float width, float height);

}  // namespace lucent::viewer
