// renderer.cpp: lucent.Renderer: a live renderer, built once (scene upload, shaders, the method's precomputation)
// and then rendered many times with new cameras and edits, as the viewer does: only what an edit touches is redone
// (lucent::Renderer::scene_changed), and frames accumulate while nothing but the frame count changes.
#include <cmath>
#include <memory>

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
      const CurrentContext current;
      if (current.generation() == generation) {
        target.reset();
        renderer.reset();
        return;
      }
    } catch (...) {  // no context can be made: nothing to delete the objects in
    }
    (void)target.release();
    (void)renderer.release();
  }
};

// Three finite numbers.
glm::vec3 vector3(const py::handle& value, const std::string& what) {
  if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value) || py::len(value) != 3)
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
      try {
        fov = py::cast<double>(item);
      } catch (const py::cast_error&) {
        throw py::type_error("camera.fov_y_deg: expected a number");
      }
      if (!(fov > 0.0 && fov < 180.0))
        throw py::value_error(fmt::format("camera.fov_y_deg: {} is out of range; allowed range (0, 180) degrees", fov));
      camera.fov_y_deg = static_cast<float>(fov);
    } else {
      throw py::value_error(fmt::format("camera: unknown key '{}'; known keys: eye, target, up, fov_y_deg", name));
    }
  }
  const glm::vec3 forward = camera.target - camera.eye;
  if (!(glm::length(forward) > 0.0f)) throw py::value_error("camera: eye and target are the same point");
  if (!(glm::length(glm::cross(forward, camera.up)) > 1e-6f * glm::length(forward) * glm::length(camera.up)))
    throw py::value_error("camera.up: zero, or parallel to the view direction (target - eye)");
  return camera;
}

class PyRenderer final : public ContextResident {
 public:
  PyRenderer(const SceneHandle& scene, const RenderArguments& arguments, const py::handle& progress)
      : handle_(scene) {
    // The keyword arguments become the handle's own overrides, so that later edits (set) come after them.
    const std::vector<std::string> extra = render_overrides(arguments);
    handle_.overrides.insert(handle_.overrides.end(), extra.begin(), extra.end());
    handle_.scene = emitting_warnings([&] { return handle_.with({}); });
    const Scene& built_scene = handle_.scene;
    camera_ = built_scene.camera;

    auto built = std::make_shared<Built>();
    run_staged_call(
        [built, built_scene](LongCallControl& control) {
          const CurrentContext current;
          built->generation = current.generation();
          const RenderProgress report = [&control](std::string_view step, double fraction) {
            if (control.stop) throw BuildInterrupted{};
            control.set_step(step);
            control.fraction = fraction;
          };
          try {
            control.set_step("renderer");
            control.fraction = 0.0;
            auto renderer = std::make_unique<Renderer>(built_scene, report);
            if (control.stop) return;
            auto target = std::make_unique<OffscreenFramebuffer>(built_scene.render.width, built_scene.render.height);
            control.set_step("renderer");
            control.fraction = 1.0;
            built->renderer = std::move(renderer);  // kept only if the call still waits (see Built)
            built->target = std::move(target);
          } catch (const BuildInterrupted&) {
          }
        },
        progress);
    if (!built->renderer) throw Error("the renderer's build was interrupted");
    const py::gil_scoped_release unlocked;
    const CurrentContext current;
    if (current.generation() != built->generation)
      throw Error("the module's OpenGL context was replaced while the renderer was built; build it again");
    renderer_ = std::move(built->renderer);
    target_ = std::move(built->target);
    generation_ = built->generation;
    add_resident(this);
  }

  ~PyRenderer() { close(); }
  PyRenderer(const PyRenderer&) = delete;
  PyRenderer& operator=(const PyRenderer&) = delete;

  void drop_gl_objects() override {
    target_.reset();
    renderer_.reset();
  }

  void close() {
    if (!renderer_ && !target_) return;
    const py::gil_scoped_release unlocked;
    try {
      const CurrentContext current;
      if (current.generation() == generation_) {
        remove_resident(this);
        drop_gl_objects();
        return;
      }
    } catch (...) {  // the objects went with their context
    }
    drop_gl_objects();
  }
  bool closed() const { return !renderer_; }

  py::object render(int frames, const py::object& camera, bool timings, const py::handle& progress) {
    require_open();
    if (frames < 1 || frames > 1'000'000)
      throw py::value_error(fmt::format("frames: {} is out of range; allowed range [1, 1000000]", frames));
    if (!camera.is_none()) camera_ = camera_from(camera, handle_.scene, camera_);
    ImageRGBA32F radiance;
    std::vector<FrameTimings> reported;
    std::string device;
    run_long_call(
        [&](LongCallControl& control) {
          const CurrentContext current;
          require_open();
          const int width = handle_.scene.render.width, height = handle_.scene.render.height;
          for (int f = 0; f < frames && !control.stop; ++f) {
            renderer_->render(camera_, {target_->id(), width, height});
            control.fraction = static_cast<double>(f + 1) / frames;
          }
          if (control.stop) return;
          reported = renderer_->finished_frames(true);
          radiance = renderer_->read_radiance();
          device = renderer_->device();
        },
        progress);
    py::array_t<float> image = to_array(radiance);
    if (!timings) return image;
    return py::make_tuple(image, timings_dict(device, reported));
  }

  // Scene.set on the renderer's own scene, applied with the least work (live parameters and materials keep the
  // method's shaders); an edit that does not build leaves the renderer as it was and raises.
  PyRenderer& set(const std::string& key, const py::handle& value) {
    require_open();
    SceneHandle edited = handle_;
    set_value(edited, key, value);
    const Scene& now = edited.scene;
    const Camera previous_camera = handle_.scene.camera;
    run_long_call(
        [&](LongCallControl&) {
          const CurrentContext current;
          require_open();
          Scene good = renderer_->scene();
          try {
            renderer_->scene() = now;
            renderer_->scene_changed();
            if (now.render.width != good.render.width || now.render.height != good.render.height)
              target_ = std::make_unique<OffscreenFramebuffer>(now.render.width, now.render.height);
          } catch (...) {
            renderer_->scene() = std::move(good);
            renderer_->scene_changed();
            throw;
          }
        },
        py::none());
    const bool camera_edited = now.camera.eye != previous_camera.eye || now.camera.target != previous_camera.target ||
                               now.camera.up != previous_camera.up || now.camera.fov_y_deg != previous_camera.fov_y_deg;
    if (camera_edited) camera_ = now.camera;
    handle_ = std::move(edited);
    return *this;
  }

  const SceneHandle& scene() const { return handle_; }
  py::dict camera() const { return camera_dict(camera_, handle_.scene.origin); }
  int accumulated_frames() {
    require_open();
    return renderer_->accumulated_frames();
  }
  std::string device() {
    require_open();
    return renderer_->device();
  }

 private:
  void require_open() const {
    if (!renderer_)
      throw Error("this lucent.Renderer is closed (close(), lucent.release() or a new lucent.Context released its "
                  "OpenGL objects); build a new one");
  }

  SceneHandle handle_;
  Camera camera_;
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<OffscreenFramebuffer> target_;
  unsigned generation_ = 0;
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
      .def("render", &PyRenderer::render, py::kw_only(), py::arg("frames") = 1, py::arg("camera") = py::none(),
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
