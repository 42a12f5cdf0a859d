// renderer.cpp: lucent.Renderer: a live renderer, built once (scene upload, shaders, the method's precomputation)
// and then rendered many times with new cameras and edits, as the viewer does: only what an edit touches is redone
// (lucent::Renderer::scene_changed), and frames accumulate while nothing but the frame count changes.
#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "frame_timings.h"
#include "gl_context.h"
#include "image_arrays.h"
#include "long_call.h"
#include "lucent/error.h"
#include "lucent/offscreen_framebuffer.h"
#include "lucent/renderer.h"
#include "python_warnings.h"
#include "render_overrides.h"
#include "scene_handle.h"
#include "scene_values.h"

namespace lucent::python {
namespace {

struct BuildInterrupted {};  // thrown through the renderer's build by its progress callback once the call is stopped

// What a build makes, owned jointly by the waiting call and the build's thread (which may outlive an interrupted
// call). Destroyed with the module's context current when that context is still the one it was made in; after a
// release the names mean nothing, and the objects are left (their memory went with the context).
struct Built {
  std::unique_ptr<Renderer> renderer;
  std::unique_ptr<OffscreenFramebuffer> target;
  unsigned generation = 0;

  Built() = default;
  Built(const Built&) = delete;
  Built& operator=(const Built&) = delete;
  ~Built() {
    if (!renderer && !target) return;
    try {
      if (existing_context_generation() == generation) {
        const py::gil_scoped_release unlocked;
        const CurrentContext current;
        if (current.generation() == generation) {
          target.reset();
          renderer.reset();
          return;
        }
      }
    } catch (...) {  // the context cannot be made current: nothing to delete the objects in
    }
    (void)target.release();
    (void)renderer.release();
  }
};

// Where the renderer's progress callback reports: the call in flight (its LongCallControl) or none. Shared by the
// PyRenderer and the callback lucent::Renderer keeps for its later rebuilds, so neither outlives what it points at.
class ProgressSlot {
 public:
  void attach(LongCallControl* control) {
    const std::lock_guard<std::mutex> lock(mutex_);
    control_ = control;
  }
  // Reports a step's fraction to the call in flight; throws BuildInterrupted when that call was stopped.
  void report(std::string_view step, double fraction) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!control_) return;
    if (control_->stop) throw BuildInterrupted{};
    control_->set_step(step);
    control_->fraction = fraction;
  }

 private:
  std::mutex mutex_;
  LongCallControl* control_ = nullptr;
};

// Attaches a call's control to the slot for as long as the call's work runs.
class AttachedControl {
 public:
  AttachedControl(ProgressSlot& slot, LongCallControl& control) : slot_(slot) { slot_.attach(&control); }
  ~AttachedControl() { slot_.attach(nullptr); }
  AttachedControl(const AttachedControl&) = delete;
  AttachedControl& operator=(const AttachedControl&) = delete;

 private:
  ProgressSlot& slot_;
};

// Three finite numbers.
glm::vec3 vector3(const py::handle& value, const std::string& what) {
  if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) ||
      PyByteArray_Check(value.ptr()) || py::len(value) != 3)
    throw py::type_error(fmt::format("{}: expected three numbers", what));
  glm::dvec3 v{0.0};
  const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
  for (int i = 0; i < 3; ++i) {
    try {
      v[i] = py::cast<double>(items[static_cast<std::size_t>(i)]);
    } catch (const py::cast_error&) {
      throw py::type_error(fmt::format("{}: expected three numbers", what));
    }
    if (!std::isfinite(v[i])) throw py::value_error(fmt::format("{}[{}]: {} is not finite", what, i, v[i]));
    if (!(std::abs(v[i]) <= 1e9))  // the scene loader's range for positions
      throw py::value_error(fmt::format("{}[{}]: {} is out of range; allowed range [-1e9, 1e9] scene units", what, i, v[i]));
  }
  return glm::vec3(v);
}

// A camera dict as Scene.camera gives it (eye, target, up [scene units], fov_y_deg); missing keys keep `camera`'s.
Camera camera_from(const py::handle& value, const Scene& scene, Camera camera) {
  if (!py::isinstance<py::dict>(value))
    throw py::type_error("camera: expected a dict with eye, target, up and fov_y_deg (as Scene.camera gives)");
  const glm::vec3 origin(scene.origin);
  for (const auto& [key, item] : py::reinterpret_borrow<py::dict>(value)) {
    const std::string name = py::str(key);
    if (name == "eye") camera.eye = vector3(item, "camera.eye") - origin;
    else if (name == "target") camera.target = vector3(item, "camera.target") - origin;
    else if (name == "up") camera.up = vector3(item, "camera.up");
    else if (name == "fov_y_deg") {
      double fov = 0.0;
      if (py::isinstance<py::bool_>(item)) throw py::type_error("camera.fov_y_deg: expected a number");
      try {
        fov = py::cast<double>(item);
      } catch (const py::cast_error&) {
        throw py::type_error("camera.fov_y_deg: expected a number");
      }
      if (!(fov >= 1.0 && fov <= 179.0))  // the scene loader's range
        throw py::value_error(fmt::format("camera.fov_y_deg: {} is out of range; allowed range [1, 179] degrees", fov));
      camera.fov_y_deg = static_cast<float>(fov);
    } else {
      throw py::value_error(fmt::format("camera: unknown key '{}'; known keys: eye, target, up, fov_y_deg", name));
    }
  }
  const glm::vec3 forward = camera.target - camera.eye;
  const float scale = std::max({1.0f, glm::length(camera.eye), glm::length(camera.target)});
  if (!(glm::length(forward) > 1e-5f * scale))
    throw py::value_error("camera: eye and target are the same point (or closer than float precision tells apart)");
  if (!(glm::length(glm::cross(forward, camera.up)) > 1e-6f * glm::length(forward) * glm::length(camera.up)))
    throw py::value_error("camera.up: zero, or parallel to the view direction (target - eye)");
  return camera;
}

// One call at a time per renderer: a second thread's call is refused rather than interleaved.
class InUse {
 public:
  explicit InUse(std::mutex& mutex) : lock_(mutex, std::try_to_lock) {
    if (!lock_.owns_lock())
      throw Error("this lucent.Renderer is in use by another thread's call; a renderer takes one call at a time");
  }

 private:
  std::unique_lock<std::mutex> lock_;
};

class PyRenderer final : public ContextResident {
 public:
  PyRenderer(const SceneHandle& scene, const RenderArguments& arguments, const py::handle& progress)
      : handle_(scene), slot_(std::make_shared<ProgressSlot>()) {
    // The keyword arguments become the handle's own overrides, so that later edits (set) come after them.
    const std::vector<std::string> extra = render_overrides(arguments);
    handle_.overrides.insert(handle_.overrides.end(), extra.begin(), extra.end());
    handle_.scene = emitting_warnings([&] { return handle_.with({}); });
    const Scene& built_scene = handle_.scene;
    camera_ = built_scene.camera;

    auto built = std::make_shared<Built>();
    run_staged_call(
        [built, built_scene, slot = slot_](LongCallControl& control) {
          const AttachedControl attached(*slot, control);
          const CurrentContext current;
          built->generation = current.generation();
          // The renderer keeps its callback for later rebuilds: it reports through the slot, never to a call gone.
          const RenderProgress report = [slot](std::string_view step, double fraction) { slot->report(step, fraction); };
          try {
            slot->report("renderer", 0.0);
            auto renderer = std::make_unique<Renderer>(built_scene, report);
            if (control.stop) return;
            auto target = std::make_unique<OffscreenFramebuffer>(built_scene.render.width, built_scene.render.height);
            slot->report("renderer", 1.0);
            built->renderer = std::move(renderer);  // kept only if the call still waits (see Built)
            built->target = std::move(target);
          } catch (const BuildInterrupted&) {
          }
        },
        progress);
    if (!built->renderer) throw Error("the renderer's build was interrupted");
    device_ = built->renderer->device();
    const py::gil_scoped_release unlocked;
    const CurrentContext current;
    if (current.generation() != built->generation)
      throw Error("the module's OpenGL context was replaced while the renderer was built; build it again");
    renderer_ = std::move(built->renderer);
    target_ = std::move(built->target);
    generation_ = built->generation;
    add_resident(this);
  }

  ~PyRenderer() {
    try {
      close();
    } catch (...) {  // a destructor does not throw: the objects are left to their context
    }
  }
  PyRenderer(const PyRenderer&) = delete;
  PyRenderer& operator=(const PyRenderer&) = delete;

  void drop_gl_objects() override {
    target_.reset();
    renderer_.reset();
  }

  void close() {
    const InUse in_use(use_);
    if (!renderer_ && !target_) return;
    const py::gil_scoped_release unlocked;
    try {
      const CurrentContext current;
      remove_resident(this);
      if (current.generation() == generation_) {
        drop_gl_objects();
        return;
      }
    } catch (...) {  // the context cannot be made current: forget the objects with it
      forget_resident(this);
    }
    (void)target_.release();
    (void)renderer_.release();
  }
  bool closed() const { return !renderer_; }

  py::object render(const py::object& frames_value, const py::object& camera, bool timings, const py::handle& progress) {
    const InUse in_use(use_);
    require_open();
    if (!py::isinstance<py::int_>(frames_value) || py::isinstance<py::bool_>(frames_value))
      throw py::type_error("frames: expected an integer");
    const long long frames = frames_value.cast<long long>();
    if (frames < 1 || frames > 1'000'000)
      throw py::value_error(fmt::format("frames: {} is out of range; allowed range [1, 1000000]", frames));
    if (!camera.is_none()) camera_ = camera_from(camera, handle_.scene, camera_);
    const Camera view = camera_;
    const int width = handle_.scene.render.width, height = handle_.scene.render.height;
    ImageRGBA32F radiance;
    std::vector<FrameTimings> reported;
    run_long_call(
        [&](LongCallControl& control) {
          const CurrentContext current;
          require_open();
          for (long long f = 0; f < frames && !control.stop; ++f) {
            renderer_->render(view, {target_->id(), width, height});
            control.fraction = static_cast<double>(f + 1) / static_cast<double>(frames);
          }
          if (control.stop) return;
          reported = renderer_->finished_frames(true);
          radiance = renderer_->read_radiance();
        },
        progress);
    py::array_t<float> image = to_array(radiance);
    if (!timings) return image;
    return py::make_tuple(image, timings_dict(device_, reported));
  }

  // Scene.set on the renderer's own scene, applied with the least work (live parameters and materials keep the
  // method's shaders); an edit that does not build (or is interrupted) puts the last good scene back and raises.
  PyRenderer& set(const std::string& key, const py::handle& value) {
    const InUse in_use(use_);
    require_open();
    SceneHandle edited = handle_;
    set_value(edited, key, value);
    const Scene& now = edited.scene;
    const Camera previous_camera = handle_.scene.camera;
    run_long_call(
        [&](LongCallControl& control) {
          const AttachedControl attached(*slot_, control);  // a rebuild's progress polls Ctrl-C
          const CurrentContext current;
          require_open();
          Scene good = renderer_->scene();
          try {
            renderer_->scene() = now;
            renderer_->scene_changed();
            if (now.render.width != good.render.width || now.render.height != good.render.height)
              target_ = std::make_unique<OffscreenFramebuffer>(now.render.width, now.render.height);
          } catch (...) {
            const std::exception_ptr failure = std::current_exception();
            slot_->attach(nullptr);  // putting the last good scene back is not interrupted
            try {
              renderer_->scene() = std::move(good);
              renderer_->scene_changed();  // nothing is built after a failure: this rebuilds the last good scene
            } catch (...) {  // not even that builds: the renderer closes (its calls say so)
              remove_resident(this);
              drop_gl_objects();
            }
            try {
              std::rethrow_exception(failure);
            } catch (const BuildInterrupted&) {
              throw Error("the edit was interrupted; the renderer has its scene from before the edit");
            }
          }
        },
        py::none());
    const bool camera_edited = now.camera.eye != previous_camera.eye || now.camera.target != previous_camera.target ||
                               now.camera.up != previous_camera.up || now.camera.fov_y_deg != previous_camera.fov_y_deg;
    if (camera_edited) camera_ = now.camera;
    handle_ = std::move(edited);
    return *this;
  }

  // Animation time [s]: deforming objects and blob surfaces take their shape at it from the next frame on (which
  // restarts the accumulation); nothing changes in a static scene.
  void set_time(double seconds) {
    const InUse in_use(use_);
    require_open();
    if (!std::isfinite(seconds) || std::abs(seconds) > 1e9)
      throw py::value_error(fmt::format("time: {} is out of range; allowed range [-1e9, 1e9] s", seconds));
    const py::gil_scoped_release unlocked;
    const CurrentContext current;
    require_open();
    renderer_->set_time(seconds);
  }
  double time() const { return renderer_ ? renderer_->time() : 0.0; }
  // Drops the accumulated frames (and what the method cached from the scene): the next frame starts afresh.
  void restart() {
    const InUse in_use(use_);
    require_open();
    renderer_->restart();
  }

  const SceneHandle& scene() const { return handle_; }
  py::dict camera() const { return camera_dict(camera_, handle_.scene.origin); }
  int accumulated_frames() {
    const InUse in_use(use_);
    require_open();
    const py::gil_scoped_release unlocked;
    const CurrentContext current;  // the context's mutex: a release on another thread waits
    require_open();
    return renderer_->accumulated_frames();
  }
  const std::string& device() const { return device_; }

 private:
  void require_open() const {
    if (!renderer_)
      throw Error("this lucent.Renderer is closed (close(), lucent.release(), a new lucent.Context, or an edit after "
                  "which not even its last good scene built); build a new one");
  }

  SceneHandle handle_;
  Camera camera_;
  std::shared_ptr<ProgressSlot> slot_;
  std::mutex use_;
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<OffscreenFramebuffer> target_;
  unsigned generation_ = 0;
  std::string device_;
};

}  // namespace

void bind_renderer(py::module_& m) {
  py::class_<PyRenderer>(m, "Renderer",
                         "A live renderer: built once (scene upload, shaders, the method's precomputation), then "
                         "render() many times with new cameras and set() edits, as the viewer renders. Frames "
                         "accumulate while neither the camera nor the scene changes.")
      .def(py::init([](const SceneHandle& scene, py::object width, py::object height, std::optional<std::string> method,
                       py::object params, py::object seed, py::object denoise, const py::object& progress) {
             return new PyRenderer(scene,
                                   {std::move(width), std::move(height), py::none(), std::move(seed), std::move(method),
                                    std::move(params), std::move(denoise)},
                                   progress);
           }),
           py::arg("scene"), py::kw_only(), py::arg("width") = py::none(), py::arg("height") = py::none(),
           py::arg("method") = py::none(), py::arg("params") = py::none(), py::arg("seed") = py::none(),
           py::arg("denoise") = py::none(), py::arg("progress") = py::none(),
           "Builds the renderer for a copy of `scene` (later edits of that Scene do not reach it; use set()). "
           "width, height, method, params, seed and denoise as lucent.render takes them. progress: None or a "
           "callable taking (step, fraction): \"renderer\" 0 first and 1 last, between them the steps of "
           "the methods that prepare meshes, a texture atlas or a precomputation. Ctrl-C raises KeyboardInterrupt within half a second; the build then stops at its "
           "next step, on its own thread.")
      .def("render", &PyRenderer::render, py::kw_only(), py::arg("frames") = py::int_(1), py::arg("camera") = py::none(),
           py::arg("timings") = false, py::arg("progress") = py::none(),
           "Renders `frames` more frames and returns the linear radiance, float32 (height, width, 3), of all the "
           "frames accumulated since the camera or the scene last changed. camera: None (the last one) or a dict "
           "as Scene.camera gives it (eye, target, up [scene units], fov_y_deg; missing keys keep the last "
           "camera's). timings and progress as lucent.render takes them.")
      .def("set", &PyRenderer::set, py::arg("key"), py::arg("value"), py::return_value_policy::reference,
           "Edits the renderer's scene as Scene.set does (\"objects.bunny.material.eta\", \"method.K\", "
           "\"lights.0.direction\", \"render.width\", ...) and applies it with the least work: live method "
           "parameters and material edits keep the method's shaders where the method supports it, anything "
           "else rebuilds. A bad key or value, or an edit that does not build, raises and keeps the renderer as "
           "it was. Returns the renderer.")
      .def("restart", &PyRenderer::restart,
           "Drops the accumulated frames and what the method cached from the scene: the next frame starts afresh.")
      .def_property("time", &PyRenderer::time, &PyRenderer::set_time,
                    "animation time [s]: deforming objects and blob surfaces take their shape at it from the next "
                    "frame on (restarting the accumulation); a static scene does not change")
      .def("close", &PyRenderer::close, "Releases the renderer's GPU objects; later calls raise lucent.Error.")
      .def_property_readonly("closed", &PyRenderer::closed)
      .def_property_readonly("scene", &PyRenderer::scene, py::return_value_policy::copy,
                             "a copy of the renderer's scene with every edit applied")
      .def_property_readonly("camera", &PyRenderer::camera, "the camera of the last render (as Scene.camera gives it)")
      .def_property_readonly("accumulated_frames", &PyRenderer::accumulated_frames)
      .def_property_readonly("device", &PyRenderer::device, "GL renderer and version")
      .def("__enter__", [](PyRenderer& r) -> PyRenderer& { return r; }, py::return_value_policy::reference)
      .def("__exit__", [](PyRenderer& r, const py::args&) { r.close(); })
      .def("__repr__", [](const PyRenderer& r) {
        const Scene& s = r.scene().scene;
        return fmt::format("<lucent.Renderer {} method {} {}x{}{}>", s.source, s.method, s.render.width,
                           s.render.height, r.closed() ? ", closed" : "");
      });
}

}  // namespace lucent::python
