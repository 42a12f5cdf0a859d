// render_overrides.h: the keyword arguments of lucent.render and lucent.reference (size, frames, seed, method and
// its parameters) as the scene overrides they stand for, so that they are checked like --set values.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

namespace lucent::python {

// width, height, frames and seed: None or a Python value, written as JSON and checked as render.* values.
struct RenderArguments {
  pybind11::object width, height, frames, seed;
  std::optional<std::string> method;  // a registered method: replaces the scene's method and its parameters
  pybind11::object params;            // dict of method parameters (None: none)
  // lucent.render's denoise: None (the scene's), a bool (denoise.enabled) or a dict of the denoising stage's
  // parameters (enabled unless it says otherwise).
  pybind11::object denoise = pybind11::none();
};

// "render.width=W", ...; "method={"name": M, ...params}" with a method, else "method.<key>=<value>" per parameter;
// "denoise.enabled=B" or "denoise={...}".
std::vector<std::string> render_overrides(const RenderArguments& arguments);

}  // namespace lucent::python
