// viewer_session.cpp: scene loading, edits -> renderer rebuilds, and errors kept for the window.
#include "viewer/viewer_session.h"

#include <algorithm>
#include <exception>

#include <fmt/format.h>

#include "lucent/error.h"
#include "params/param_json.h"

namespace lucent::viewer {
namespace {

// Every declared parameter of `method` at its default.
ParamValues method_defaults(const std::string& method) {
  for (const ParamSection& section : scene_param_sections())
    if (section.name == method) return read_params(nlohmann::json::object(), section, {"viewer", "/method"});
  throw Error(fmt::format("unknown method '{}'", method));
}

}  // namespace

bool same_camera(const Camera& a, const Camera& b) {
  return a.eye == b.eye && a.target == b.target && a.up == b.up && a.fov_y_deg == b.fov_y_deg;
}

ViewerSession::ViewerSession(std::string scene_path, std::vector<std::string> overrides)
    : scene_path_(std::move(scene_path)), overrides_(std::move(overrides)), watcher_(scene_path_) {}

bool ViewerSession::load(bool strict) {
  try {
    Scene scene = scene_path_.empty() ? default_scene(overrides_) : load_scene(scene_path_, overrides_);
    adopt(std::move(scene));
    apply_pending();
    if (strict && !error_.empty()) throw Error(error_);
    return error_.empty();
  } catch (const Error& e) {
    if (strict) throw;
    error_ = e.what();
    return false;
  } catch (const std::exception& e) {  // e.g. std::bad_alloc: the scene is as unusable, the session goes on
    if (strict) throw;
    const std::string scene = scene_path_.empty() ? "<built-in default scene>" : scene_path_;
    error_ = fmt::format("{}: cannot load the scene: {}", scene, e.what());
    return false;
  }
}

void ViewerSession::adopt(Scene scene) {
  bool camera_changed = !file_camera_ || !same_camera(*file_camera_, scene.camera);
  file_camera_ = scene.camera;
  if (camera_changed) camera_ = OrbitCamera(scene.camera);
  method_params_.clear();
  edit_ = std::move(scene);
  pending_ = true;
}

bool ViewerSession::reload_if_changed() {
  if (!watch_ || !watcher_.changed()) return false;
  ++reloads_;
  load();
  return true;
}

void ViewerSession::set_method(const std::string& name) {
  if (name == edit_.method) return;
  method_params_[edit_.method] = edit_.method_params;
  auto known = method_params_.find(name);
  try {
    edit_.method_params = known != method_params_.end() ? known->second : method_defaults(name);
    edit_.method = name;
  } catch (const Error& e) {
    error_ = e.what();
    return;
  }
  edited();
}

// A rebuild that fails (a material out of range, a shader that does not compile) leaves the renderer with the
// last good scene, rebuilt, and the message on screen; the edit stays for the user to fix.
void ViewerSession::apply_pending() {
  if (!pending_) return;
  pending_ = false;
  if (!renderer_) {
    try {
      renderer_ = std::make_unique<Renderer>(edit_);
      error_.clear();
    } catch (const std::exception& e) {
      error_ = e.what();
    }
    return;
  }
  Scene good = renderer_->scene();
  try {
    for (std::size_t i = 0; i < edit_.objects.size(); ++i)
      if (edit_.objects[i].material) validate_material(*edit_.objects[i].material, fmt::format("objects[{}] ('{}') material", i, edit_.objects[i].name));
    renderer_->scene() = edit_;
    renderer_->scene_changed();
    error_.clear();
  } catch (const std::exception& e) {
    error_ = e.what();
    try {
      renderer_->scene() = std::move(good);
      renderer_->scene_changed();
    } catch (const std::exception&) {
      renderer_.reset();  // not even the last good scene builds: an empty view with the message
    }
  }
}

void ViewerSession::render(const RenderTarget& target) {
  apply_pending();
  if (!renderer_) return;
  try {
    renderer_->render(camera_.camera(), target);
  } catch (const std::exception& e) {
    error_ = e.what();
    renderer_.reset();
  }
}

Scene ViewerSession::scene_for_saving(int view_width, int view_height) const {
  Scene scene = renderer_ ? renderer_->scene() : edit_;
  scene.camera = camera_.camera();
  scene.render.width = view_width;
  scene.render.height = view_height;
  if (renderer_) scene.render.frames = std::max(1, renderer_->accumulated_frames());
  return scene;
}

}  // namespace lucent::viewer
