// reference.cpp: lucent.reference: the CPU ground truth of `lucent reference` (volumetric path tracing or the
// BSSRDF model), returned as the mean radiance and its per-pixel standard error.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "image_arrays.h"
#include "lucent/error.h"
#include "reference/reference_renderer.h"
#include "render_overrides.h"
#include "scene_handle.h"

namespace lucent::python {
namespace {

reference::ReferenceSettings settings_of(const std::string& integrator, int spp, unsigned long long seed,
                                         int threads, bool jitter, int max_scatter, double time_seconds) {
  if (integrator != "volpath" && integrator != "bssrdf")
    throw Error(fmt::format("integrator: '{}' is not one of volpath, bssrdf", integrator));
  if (spp < 1) throw Error(fmt::format("spp: {} is out of range; allowed range [1, 1000000000]", spp));
  if (threads < 0) throw Error(fmt::format("threads: {} is out of range; allowed range [0, 4096]", threads));
  if (max_scatter < 0)
    throw Error(fmt::format("max_scatter: {} is out of range; allowed range [0, 1000000000]", max_scatter));
  reference::ReferenceSettings s;
  s.integrator = integrator == "volpath" ? reference::Integrator::Volpath : reference::Integrator::Bssrdf;
  if (max_scatter > 0 && s.integrator != reference::Integrator::Volpath)
    throw Error("max_scatter: only the volpath integrator counts scattering events");
  s.samples_per_pixel = spp, s.seed = seed, s.threads = threads, s.jitter = jitter;
  s.max_scatter = max_scatter, s.time_seconds = time_seconds;
  return s;
}

py::tuple render_reference_arrays(const SceneHandle& handle, const RenderArguments& arguments,
                                  const reference::ReferenceSettings& settings) {
  const Scene scene = handle.with(render_overrides(arguments));
  reference::ReferenceImage image;
  {
    py::gil_scoped_release unlocked;
    image = reference::render_reference(scene, settings);
  }
  return py::make_tuple(to_array(image.mean), to_array(image.standard_error));
}

}  // namespace

void bind_reference(py::module_& m) {
  m.def(
      "reference",
      [](const SceneHandle& scene, const std::string& integrator, int spp, unsigned long long seed, int threads,
         bool jitter, int max_scatter, double time, std::optional<int> width, std::optional<int> height) {
        return render_reference_arrays(scene, {width, height, {}, {}, {}, py::none()},
                                       settings_of(integrator, spp, seed, threads, jitter, max_scatter, time));
      },
      py::arg("scene"), py::kw_only(), py::arg("integrator") = "volpath", py::arg("spp") = 16, py::arg("seed") = 1,
      py::arg("threads") = 0, py::arg("jitter") = false, py::arg("max_scatter") = 0, py::arg("time") = 0.0,
      py::arg("width") = py::none(), py::arg("height") = py::none(),
      "Renders the CPU reference as `lucent reference` does: integrator \"volpath\" (the physics) or \"bssrdf\" "
      "(the model), spp samples per pixel, threads (0: all cores), jitter (rays jittered inside pixels; default "
      "pixel centres), max_scatter (volpath: end paths after this many scattering events; 0: no limit), time "
      "[s] for animated scenes. Returns (mean, standard_error), each float32 (height, width, 3).");
}

}  // namespace lucent::python
