// command_view.cpp: `lucent view [SCENE]`: the interactive viewer (viewer/), or N frames and a screenshot.


#include "commands.h"
#include "lucent/error.h"
#include "viewer/viewer_app.h"

namespace lucent::cli {

void add_view_command(CLI::App& app) {
  auto options = std::make_shared<viewer::ViewerOptions>();
  CLI::App* cmd = app.add_subcommand("view", "interactive viewer: a window with the scene and a panel of its parameters");
  cmd->add_option("scene", options->scene_path, "scene file (JSON); the built-in default scene when omitted");
  cmd->add_option("--set", options->sets, "override a scene value, e.g. --set method.K=8 (as lucent render)");
  add_no_cache_flag(cmd);
  cmd->add_option("--width", options->width, "rendered view width in pixels (default: render.width)")->check(CLI::Range(1, 16384));
  cmd->add_option("--height", options->height, "rendered view height in pixels (default: render.height)")->check(CLI::Range(1, 16384));
  cmd->add_option("--frames", options->frames, "render this many frames, write the screenshots and exit")->check(CLI::Range(1, 1000000));
  cmd->add_option("--screenshot", options->screenshot,
                  "with --frames: the rendered view (not the panel) as .png (tone-mapped) or .exr (radiance)");
  cmd->add_option("--screenshot-window", options->screenshot_window, "with --frames: the whole window, panel included (.png)");
  cmd->add_option("--save-scene", options->save_scene,
                  "with --frames: save the scene as the panel's \"save scene as\" does: .json (lucent render of it reproduces "
                  "the view) or .gltf/.glb (one glTF file for Blender and glTF viewers, as lucent export)");
  cmd->add_option("--panel-width", options->panel_width, "panel width in pixels (at most half the window)")
      ->check(CLI::Range(160, 2000));
  cmd->add_option("--window-width", options->window_width,
                  "window width in pixels (default: the view at an integer scale beside the panel; the view is "
                  "scaled to fit, its rendered size stays --width x --height)")
      ->check(CLI::Range(100, 16384));
  cmd->add_option("--window-height", options->window_height, "window height in pixels")->check(CLI::Range(100, 16384));
  cmd->footer(
      "\nControls: left drag orbit, right/middle or shift+left drag pan, wheel zoom, R reset camera, P screenshot,\n"
      "Esc quit. The scene file is reloaded when it changes on disk; errors show in the window.\n"
      "The view is rendered at --width x --height and scaled to fit the window beside the panel (aspect kept);\n"
      "the panel's first line says which frame is rendering and how long a frame takes.");
  cmd->callback([options] {
    if ((!options->screenshot.empty() || !options->screenshot_window.empty() || !options->save_scene.empty()) &&
        options->frames == 0)
      throw Error("view: --screenshot, --screenshot-window and --save-scene need --frames N (in the window: the panel's PNG/EXR buttons)");
    viewer::run_viewer(*options);
  });
}

}  // namespace lucent::cli
