// viewer_session.h: the scene the viewer shows: loading (a file or the built-in scene) and reloading, the
// renderer, edits from the panel applied as one restart per frame, and the last error for the window to
// show. A failed load or rebuild keeps the last good renderer (or none), never ends the session.
#pragma once
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lucent/renderer.h"
#include "lucent/scene.h"
#include "viewer/file_watcher.h"
#include "viewer/orbit_camera.h"

namespace lucent::viewer {

// The same view: eye, target, up and field of view equal.
bool same_camera(const Camera& a, const Camera& b);

class ViewerSession {
 public:
  // `scene_path` "" = the built-in default scene; `overrides` as `lucent render --set`.
  ViewerSession(std::string scene_path, std::vector<std::string> overrides);

  // Loads the scene (needs a current GL context for the renderer). Every std::exception (lucent::Error, and
  // std::bad_alloc or another from a reader) is kept for display; `strict`: rethrown instead (the --frames mode,
  // which must fail like `lucent render`). True on success.
  bool load(bool strict = false);
  // Reloads when the scene file changed on disk; true when it did (successfully or not).
  bool reload_if_changed();

  // The scene as the panel edits it; call edited() after a change. The renderer sees it at the next frame.
  Scene& edit() { return edit_; }
  void edited() { pending_ = true; }
  void set_method(const std::string& name);  // keeps each method's parameters while switching back and forth

  // Applies pending edits, then renders one frame (nothing without a renderer). Errors are kept, not thrown.
  void render(const RenderTarget& target);
  void restart() { pending_ = true; }
  bool pending() const { return pending_; }

  Renderer* renderer() { return renderer_.get(); }
  OrbitCamera& camera() { return camera_; }
  const std::string& error() const { return error_; }
  void clear_error() { error_.clear(); }
  void set_error(std::string message) { error_ = std::move(message); }
  const std::string& scene_path() const { return scene_path_; }
  bool watching() const { return watch_; }
  void set_watching(bool on) { watch_ = on; }
  int reload_count() const { return reloads_; }

  // The scene as it would be saved: the edits, the current camera, `view_size` and the frames accumulated,
  // so that `lucent render` of the saved file reproduces the view.
  Scene scene_for_saving(int view_width, int view_height) const;

 private:
  void apply_pending();
  void adopt(Scene scene);

  std::string scene_path_;
  std::vector<std::string> overrides_;
  FileWatcher watcher_;
  bool watch_ = true;
  int reloads_ = 0;
  std::unique_ptr<Renderer> renderer_;
  Scene edit_;
  std::optional<Camera> file_camera_;  // the camera of the last loaded file (a reload keeps the user's view
                                       // unless the file's camera changed)
  std::map<std::string, ParamValues> method_params_;  // by method name, for switching back
  OrbitCamera camera_;
  bool pending_ = false;
  std::string error_;
};

}  // namespace lucent::viewer
