// render_overrides.cpp: keyword arguments to --set overrides.
#include "render_overrides.h"

#include <fmt/format.h>

#include "bindings.h"

namespace lucent::python {

std::vector<std::string> render_overrides(const RenderArguments& a) {
  std::vector<std::string> overrides;
  const std::pair<const char*, const pybind11::object&> render_values[] = {
      {"width", a.width}, {"height", a.height}, {"frames", a.frames}, {"seed", a.seed}};
  for (const auto& [key, value] : render_values)
    if (value && !value.is_none()) overrides.push_back(fmt::format("render.{}={}", key, to_json_text(value)));
  if (a.denoise && !a.denoise.is_none()) {
    if (py::isinstance<py::bool_>(a.denoise)) {
      overrides.push_back(fmt::format("denoise.enabled={}", a.denoise.cast<bool>() ? "true" : "false"));
    } else {
      py::dict denoise = py::dict(a.denoise);
      if (!denoise.contains("enabled")) denoise["enabled"] = true;
      overrides.push_back("denoise=" + to_json_text(denoise));
    }
  }
  py::dict params = a.params.is_none() ? py::dict() : py::dict(a.params);
  if (a.method) {
    py::dict method;
    method["name"] = *a.method;
    for (auto [key, value] : params) method[key] = value;
    overrides.push_back("method=" + to_json_text(method));
    return overrides;
  }
  for (auto [key, value] : params)
    overrides.push_back(fmt::format("method.{}={}", py::str(key).cast<std::string>(), to_json_text(value)));
  return overrides;
}

}  // namespace lucent::python
