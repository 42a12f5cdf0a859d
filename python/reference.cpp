// reference.cpp: lucent.reference: the CPU ground truth of `lucent reference` (volumetric path tracing or the
// BSSRDF model), returned as the mean radiance and its per-pixel standard error.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "arguments.h"
#include "bindings.h"
#include "image_arrays.h"
#include "long_call.h"
#include "lucent/error.h"
#include "params/argument_ranges.h"
#include "python_warnings.h"
#include "reference/reference_renderer.h"
#include "render_overrides.h"
#include "scene_handle.h"

namespace lucent::python {
namespace {

// The keyword arguments in the ranges of `lucent reference`'s options (argument_ranges.h).
reference::ReferenceSettings settings_of(const std::string& integrator, const py::handle& spp, const py::handle& seed,
                                         const py::handle& threads, bool jitter, const py::handle& max_scatter,
                                         const py::handle& time, bool sphere_jumps) {
  using namespace argument_ranges;
  if (integrator != "volpath" && integrator != "bssrdf")
    throw Error(fmt::format("integrator: '{}' is not one of volpath, bssrdf", integrator));
  reference::ReferenceSettings s;
  s.integrator = integrator == "volpath" ? reference::Integrator::Volpath : reference::Integrator::Bssrdf;
  s.samples_per_pixel = static_cast<int>(whole_argument(spp, kSamplesPerPixel, "spp"));
  s.seed = whole_argument(seed, kReferenceSeed, "seed");
  s.threads = static_cast<int>(whole_argument(threads, kThreads, "threads"));
  s.jitter = jitter;
  s.max_scatter = static_cast<int>(whole_argument(max_scatter, kMaxScatter, "max_scatter"));
  if (s.max_scatter > 0 && s.integrator != reference::Integrator::Volpath)
    throw Error("max_scatter: only the volpath integrator counts scattering events");
  s.time_seconds = number_argument(time, kTimeSeconds, "time");
  s.sphere_jumps = sphere_jumps;
  return s;
}

py::tuple render_reference_arrays(const SceneHandle& handle, const RenderArguments& arguments,
                                  reference::ReferenceSettings settings, const py::handle& progress) {
  const Scene scene = emitting_warnings([&] { return handle.with(render_overrides(arguments)); });
  reference::ReferenceImage image;
  run_long_call(
      [&](LongCallControl& control) {
        settings.progress = [&control](double fraction) { control.fraction = fraction; };
        settings.stop_requested = [&control] { return control.stop.load(); };
        image = reference::render_reference(scene, settings);
      },
      progress);
  return py::make_tuple(to_array(image.mean), to_array(image.standard_error));
}

}  // namespace

void bind_reference(py::module_& m) {
  m.def(
      "reference",
      [](const SceneHandle& scene, const std::string& integrator, const py::object& spp, const py::object& seed,
         const py::object& threads, bool jitter, const py::object& max_scatter, const py::object& time,
         py::object width, py::object height, bool sphere_jumps, const py::object& progress) {
        return render_reference_arrays(scene,
                                       {std::move(width), std::move(height), py::none(), py::none(), {}, py::none(), py::none()},
                                       settings_of(integrator, spp, seed, threads, jitter, max_scatter, time, sphere_jumps),
                                       progress);
      },
      py::arg("scene"), py::kw_only(), py::arg("integrator") = "volpath", py::arg("spp") = 16, py::arg("seed") = 1,
      py::arg("threads") = 0, py::arg("jitter") = false, py::arg("max_scatter") = 0, py::arg("time") = 0.0,
      py::arg("width") = py::none(), py::arg("height") = py::none(), py::arg("sphere_jumps") = true,
      py::arg("progress") = py::none(),
      "Renders the CPU reference as `lucent reference` does: integrator \"volpath\" (the physics) or \"bssrdf\" "
      "(the model), spp samples per pixel, threads (0: all cores), jitter (rays jittered inside pixels; default "
      "pixel centres), max_scatter (volpath: end paths after this many scattering events; 0: no limit), time "
      "[s] for animated scenes, in [0, 1e9], sphere_jumps (volpath: jump across spheres deep inside homogeneous "
      "media; the same image). The numbers have the ranges of `lucent reference`'s options. "
      "progress: None or a callable taking the fraction done in [0, 1], called on the calling thread about every "
      "50 ms while the render runs and with 1.0 at its end. Ctrl-C (SIGINT) raises KeyboardInterrupt within a "
      "fraction of a second, as does an exception raised by progress; nothing is returned then. "
      "Returns (mean, standard_error), each float32 (height, width, 3).");
}

}  // namespace lucent::python
