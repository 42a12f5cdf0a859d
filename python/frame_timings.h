// frame_timings.h: a frame's GPU times and statistics as the dict lucent.render(timings=True) and
// lucent.Renderer.render(timings=True) return.
#pragma once
#include <vector>

#include <pybind11/pybind11.h>

#include "lucent/renderer.h"

namespace lucent::python {

// {"frame", "total_ms", "passes": {name: ms}, "stats": {name: value}}
pybind11::dict frame_dict(const FrameTimings& timings);
// {"device": device, "frames": [frame_dict, ...]}
pybind11::dict timings_dict(const std::string& device, const std::vector<FrameTimings>& frames);

}  // namespace lucent::python
