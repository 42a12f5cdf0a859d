// render_overrides.cpp: keyword arguments to --set overrides.
#include "render_overrides.h"

#include <fmt/format.h>

#include "bindings.h"

namespace lucent::python {

std::vector<std::string> render_overrides(const RenderArguments& a) {
  std::vector<std::string> overrides;
  if (a.width) overrides.push_back(fmt::format("render.width={}", *a.width));
  if (a.height) overrides.push_back(fmt::format("render.height={}", *a.height));
  if (a.frames) overrides.push_back(fmt::format("render.frames={}", *a.frames));
  if (a.seed) overrides.push_back(fmt::format("render.seed={}", *a.seed));
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
