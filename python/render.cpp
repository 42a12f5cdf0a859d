// render.cpp: lucent.render: a real-time render with any registered method, as `lucent render` does, returned as
// linear radiance. The module's headless OpenGL context (gl_context.h) serves every render, from any thread.

#include <pybind11/stl.h>

#include "bindings.h"
#include "frame_timings.h"
#include "image_arrays.h"
#include "gl_context.h"
#include "long_call.h"
#include "lucent/offscreen_framebuffer.h"
#include "lucent/renderer.h"
#include "python_warnings.h"
#include "render_overrides.h"
#include "scene_handle.h"

namespace lucent::python {
namespace {

struct RenderResult {
  ImageRGBA32F radiance;
  std::vector<FrameTimings> frames;
  std::string device;
};

// The frames, stopped early when control.stop is set (the result is then unused).
RenderResult render_frames(const Scene& scene, LongCallControl& control) {
  const CurrentContext current;  // released after the renderer and framebuffer below are gone
  Renderer renderer(scene);
  const int width = scene.render.width, height = scene.render.height;
  OffscreenFramebuffer target(width, height);
  for (int f = 0; f < scene.render.frames && !control.stop; ++f) {
    renderer.render(scene.camera, {target.id(), width, height});
    control.fraction = static_cast<double>(f + 1) / scene.render.frames;
  }
  if (control.stop) return {};
  RenderResult result;
  result.frames = renderer.finished_frames(true);
  result.radiance = renderer.read_radiance();
  result.device = renderer.device();
  return result;
}

py::object render(const SceneHandle& handle, const RenderArguments& arguments, bool timings,
                  const py::handle& progress) {
  const Scene scene = emitting_warnings([&] { return handle.with(render_overrides(arguments)); });
  RenderResult result;
  run_long_call([&](LongCallControl& control) { result = render_frames(scene, control); }, progress);
  py::array_t<float> image = to_array(result.radiance);
  if (!timings) return image;
  return py::make_tuple(image, timings_dict(result.device, result.frames));
}

}  // namespace

void bind_render(py::module_& m) {
  m.def(
      "render",
      [](const SceneHandle& scene, py::object width, py::object height, py::object frames,
         std::optional<std::string> method, py::object params, py::object seed, py::object denoise, bool timings,
         const py::object& progress) {
        return render(scene, {std::move(width), std::move(height), std::move(frames), std::move(seed),
                              std::move(method), std::move(params), std::move(denoise)},
                      timings, progress);
      },
      py::arg("scene"), py::kw_only(), py::arg("width") = py::none(), py::arg("height") = py::none(),
      py::arg("frames") = py::none(), py::arg("method") = py::none(), py::arg("params") = py::none(),
      py::arg("seed") = py::none(), py::arg("denoise") = py::none(), py::arg("timings") = false,
      py::arg("progress") = py::none(),
      "Renders the scene headless as `lucent render` does and returns the linear radiance, float32 of shape "
      "(height, width, 3). width, height, frames and seed override render.*; method replaces the scene's method "
      "(its parameters from params, else the defaults); params alone override method.<key>. denoise: True, False or a dict of the "
      "denoising stage's parameters (`lucent render --help`, [denoise]; enabled unless the dict says otherwise): the "
      "filtered image instead of the method's raw average. With timings=True "
      "returns (image, {\"device\": ..., \"frames\": [{\"frame\", \"total_ms\", \"passes\", \"stats\"}, ...]}) "
      "with each frame's GPU times [ms]. progress: None or a callable taking the fraction of frames done, called "
      "on the calling thread; Ctrl-C raises KeyboardInterrupt after the frame in flight. The OpenGL context is the "
      "module's (lucent.Context, lucent.release).");
}

}  // namespace lucent::python
