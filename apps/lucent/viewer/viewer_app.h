// viewer_app.h: `lucent view`: a GLFW window showing a scene rendered by lucent::Renderer (the library's
// passes, as `lucent render`) beside an ImGui panel; or, with `frames`, N frames and screenshots, then exit.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace lucent::viewer {

struct ViewerOptions {
  std::string scene_path;             // "" = the built-in default scene
  std::vector<std::string> sets;      // --set overrides, as `lucent render`
  std::optional<int> width, height;   // rendered view [pixels]; default: the scene's render.width/height
  int frames = 0;                     // > 0: render this many frames, write the screenshots, exit
  std::string screenshot;             // with frames: the rendered view only (.png tone-mapped, .exr radiance)
  std::string screenshot_window;      // with frames: the whole window, panel included (.png)
  std::string save_scene;             // with frames: "save scene as" after the last frame
  int panel_width = 380;              // [pixels] at most half the window
  std::optional<int> window_width, window_height;  // [pixels] default: the view at an integer scale beside the panel
};

// Throws lucent::Error when no window can be opened, and with `frames` when the scene does not load or render.
void run_viewer(const ViewerOptions& options);

}  // namespace lucent::viewer
