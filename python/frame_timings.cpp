// frame_timings.cpp: see frame_timings.h.
#include "frame_timings.h"

#include "bindings.h"

namespace lucent::python {

py::dict frame_dict(const FrameTimings& t) {
  py::dict passes, stats;
  for (const PassTiming& p : t.passes) passes[py::str(p.name)] = p.ms;
  for (const FrameStatistic& s : t.stats) stats[py::str(s.name)] = s.value;
  py::dict frame;
  frame["frame"] = t.frame, frame["total_ms"] = t.total_ms, frame["passes"] = passes, frame["stats"] = stats;
  return frame;
}

py::dict timings_dict(const std::string& device, const std::vector<FrameTimings>& frames) {
  py::list list;
  for (const FrameTimings& t : frames) list.append(frame_dict(t));
  py::dict info;
  info["device"] = device, info["frames"] = list;
  return info;
}

}  // namespace lucent::python
