// render.cpp: lucent.render: a real-time render with any registered method, as `lucent render` does, returned as
// linear radiance. One headless OpenGL context serves every render of the process, from any thread.
#include <mutex>

#include <pybind11/stl.h>

#include "bindings.h"
#include "image_arrays.h"
#include "lucent/context.h"
#include "lucent/offscreen_framebuffer.h"
#include "lucent/renderer.h"
#include "render_overrides.h"
#include "scene_handle.h"

namespace lucent::python {
namespace {

// Created at the first render and never destroyed: tearing EGL down while the interpreter exits (after the
// driver's own atexit handlers may have run) is not safe, and the process ends right after.
GLContext& headless_context() {
  static GLContext* context = create_headless_context().release();
  return *context;
}

// Renders from any Python thread, one at a time: a GL context is current on one thread at a time, so each render
// holds this lock, makes the context current on its thread and lets go of it when done.
std::mutex render_mutex;

class CurrentContext {
 public:
  CurrentContext() : context_(headless_context()) { context_.make_current(); }
  ~CurrentContext() { context_.release_current(); }
  CurrentContext(const CurrentContext&) = delete;
  CurrentContext& operator=(const CurrentContext&) = delete;

 private:
  GLContext& context_;
};

struct RenderResult {
  ImageRGBA32F radiance;
  std::vector<FrameTimings> frames;
  std::string device;
};

RenderResult render_frames(const Scene& scene) {
  const std::lock_guard<std::mutex> lock(render_mutex);
  const CurrentContext current;  // released after the renderer and framebuffer below are gone
  Renderer renderer(scene);
  const int width = scene.render.width, height = scene.render.height;
  OffscreenFramebuffer target(width, height);
  for (int f = 0; f < scene.render.frames; ++f) renderer.render(scene.camera, {target.id(), width, height});
  RenderResult result;
  result.frames = renderer.finished_frames(true);
  result.radiance = renderer.read_radiance();
  result.device = renderer.device();
  return result;
}

py::dict frame_dict(const FrameTimings& t) {
  py::dict passes, stats;
  for (const PassTiming& p : t.passes) passes[py::str(p.name)] = p.ms;
  for (const FrameStatistic& s : t.stats) stats[py::str(s.name)] = s.value;
  py::dict frame;
  frame["frame"] = t.frame, frame["total_ms"] = t.total_ms, frame["passes"] = passes, frame["stats"] = stats;
  return frame;
}

py::object render(const SceneHandle& handle, const RenderArguments& arguments, bool timings) {
  const Scene scene = handle.with(render_overrides(arguments));
  RenderResult result;
  {
    py::gil_scoped_release unlocked;
    result = render_frames(scene);
  }
  py::array_t<float> image = to_array(result.radiance);
  if (!timings) return image;
  py::list frames;
  for (const FrameTimings& t : result.frames) frames.append(frame_dict(t));
  py::dict info;
  info["device"] = result.device, info["frames"] = frames;
  return py::make_tuple(image, info);
}

}  // namespace

void bind_render(py::module_& m) {
  m.def(
      "render",
      [](const SceneHandle& scene, py::object width, py::object height, py::object frames,
         std::optional<std::string> method, py::object params, py::object seed, bool timings) {
        return render(scene, {std::move(width), std::move(height), std::move(frames), std::move(seed),
                              std::move(method), std::move(params)},
                      timings);
      },
      py::arg("scene"), py::kw_only(), py::arg("width") = py::none(), py::arg("height") = py::none(),
      py::arg("frames") = py::none(), py::arg("method") = py::none(), py::arg("params") = py::none(),
      py::arg("seed") = py::none(), py::arg("timings") = false,
      "Renders the scene headless as `lucent render` does and returns the linear radiance, float32 of shape "
      "(height, width, 3). width, height, frames and seed override render.*; method replaces the scene's method "
      "(its parameters from params, else the defaults); params alone override method.<key>. With timings=True "
      "returns (image, {\"device\": ..., \"frames\": [{\"frame\", \"total_ms\", \"passes\", \"stats\"}, ...]}) "
      "with each frame's GPU times [ms].");
}

}  // namespace lucent::python
