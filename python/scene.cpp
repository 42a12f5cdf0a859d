// scene.cpp: lucent.load_scene and lucent.Scene.
#include <algorithm>
#include <regex>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "lucent/error.h"
#include "python_warnings.h"
#include "scene_handle.h"
#include "scene_values.h"

namespace lucent::python {
namespace {

Scene load(const std::optional<std::string>& path, const std::vector<std::string>& overrides) {
  return path ? load_scene(*path, overrides) : default_scene(overrides);
}

// "/objects/0/material" -> "objects.0.material".
std::string dotted(std::string pointer) {
  if (!pointer.empty() && pointer[0] == '/') pointer.erase(0, 1);
  std::replace(pointer.begin(), pointer.end(), '/', '.');
  return pointer;
}

// The loader names an override as the CLI's option ("--set 'method.K=0': /method/K: 0 is out of range; ...");
// Python names the key it was given ("method.K: 0 is out of range; ..."). A wrong type raises TypeError, a value
// out of its range or choices ValueError, anything else lucent.Error.
[[noreturn]] void raise_in_python_terms(const Error& error) {
  static const std::regex at_pointer(R"(^--set '.*?': (/[^ :]*): (.*)$)"), without_pointer(R"(^--set '(.*?)': (.*)$)");
  static const std::regex unknown_method_key(R"(^method\.([^.]+): unknown key; known keys: (.*)$)");
  const std::string message = error.what();
  std::smatch match;
  std::string text = message;
  if (std::regex_match(message, match, at_pointer)) text = dotted(match[1]) + ": " + match[2].str();
  else if (std::regex_match(message, match, without_pointer))
    text = match[1].str().substr(0, match[1].str().find('=')) + ": " + match[2].str();
  if (text == message) throw;  // not about an override: the message as it was
  if (std::regex_match(text, match, unknown_method_key))
    throw Error(fmt::format("unknown method parameter '{}'; known: {}", match[1].str(), match[2].str()));
  const std::string problem = text.substr(text.find(": ") + 2);
  if (problem.starts_with("expected ")) throw py::type_error(text);
  for (const char* value_problem : {"out of range", "is not finite", "is not one of", "is not an integer",
                                    "NaN is not allowed"})
    if (problem.find(value_problem) != std::string::npos) throw py::value_error(text);
  throw Error(text);
}

Scene load_in_python_terms(const std::optional<std::string>& path, const std::vector<std::string>& overrides) {
  try {
    return load(path, overrides);
  } catch (const Error& error) {
    raise_in_python_terms(error);
  }
}

}  // namespace

SceneHandle& set_value(SceneHandle& handle, const std::string& key, const py::handle& value) {
  std::vector<std::string> overrides = handle.overrides;
  overrides.push_back(fmt::format("{}={}", key, to_json_text(value)));
  handle.scene = emitting_warnings([&] { return load_in_python_terms(handle.path, overrides); });
  handle.overrides = std::move(overrides);
  return handle;
}

SceneHandle::SceneHandle(std::optional<std::string> path_, std::vector<std::string> overrides_)
    : path(std::move(path_)),
      overrides(std::move(overrides_)),
      scene(emitting_warnings([this] { return load_in_python_terms(path, overrides); })) {}

Scene SceneHandle::with(const std::vector<std::string>& extra) const {
  std::vector<std::string> all = overrides;
  all.insert(all.end(), extra.begin(), extra.end());
  return load_in_python_terms(path, all);
}

void bind_scene(py::module_& m) {
  bind_scene_values(m);
  py::class_<SceneHandle>(m, "Scene", "A scene file (or the built-in default scene) with --set style overrides.")
      .def_readonly("path", &SceneHandle::path, "the scene file; None for the built-in default scene")
      .def_readonly("overrides", &SceneHandle::overrides, "the \"key.path=value\" overrides, in order")
      .def("set", &set_value, py::arg("key"), py::arg("value"), py::return_value_policy::reference,
           "Overrides a scene value as `lucent render --set key=value` does (value: a number, string, bool, "
           "list, dict or numpy array, written as JSON), e.g. set(\"objects.bunny.material\", \"Marble\"), "
           "set(\"objects.0.material.eta\", 1.4), set(\"method.K\", 8). Array elements by index or by their "
           "name. Raises TypeError for a value of the wrong type, ValueError for one out of range, lucent.Error "
           "otherwise, and keeps the scene as it was. Returns the scene.")
      .def_property_readonly("source", [](const SceneHandle& h) { return h.scene.source; })
      .def_property_readonly("method", [](const SceneHandle& h) { return h.scene.method; })
      .def_property_readonly("method_params", [](const SceneHandle& h) { return method_params_dict(h.scene); },
                             "the method's parameters, every declared one (defaults filled in), typed as declared")
      .def_property_readonly("width", [](const SceneHandle& h) { return h.scene.render.width; })
      .def_property_readonly("height", [](const SceneHandle& h) { return h.scene.render.height; })
      .def_property_readonly("frames", [](const SceneHandle& h) { return h.scene.render.frames; })
      .def_property_readonly("seed", [](const SceneHandle& h) { return h.scene.render.seed; })
      .def_property_readonly("exposure", [](const SceneHandle& h) { return decimal(h.scene.render.exposure); },
                             "render.exposure [stops], as lucent.tonemap takes it")
      .def_property_readonly("tonemap", [](const SceneHandle& h) { return tonemap_name(h.scene.render.tonemap); },
                             "render.tonemap, the operator lucent.tonemap takes")
      .def_property_readonly("camera", [](const SceneHandle& h) { return camera_dict(h.scene.camera, h.scene.origin); },
                             "eye, target, up [scene units] and fov_y_deg")
      .def_property_readonly("scale_mm", [](const SceneHandle& h) { return h.scene.scale_mm; },
                             "millimetres per scene unit")
      .def_property_readonly("objects", [](const SceneHandle& h) { return objects_of(h.scene); },
                             "the objects (lucent.SceneObject) in order, by index or name: objects[\"bunny\"].material; "
                             "objects.names() lists the names; set(\"objects.<name or index>.<key>\", value) changes them")
      .def_property_readonly("lights", [](const SceneHandle& h) { return lights_of(h.scene); },
                             "the lights as dicts (type, direction, radiance, position, intensity, ...): directional "
                             "lights, then point and spot lights, then an environment map's samples")
      .def("__repr__", [](const SceneHandle& h) {
        return fmt::format("<lucent.Scene {} method {} {}x{}, {} override(s)>", h.scene.source, h.scene.method,
                           h.scene.render.width, h.scene.render.height, h.overrides.size());
      });
  m.def(
      "load_scene",
      [](std::optional<std::string> path, std::vector<std::string> overrides) {
        return SceneHandle(std::move(path), std::move(overrides));
      },
      py::arg("path") = py::none(), py::arg("overrides") = std::vector<std::string>{},
      "Loads a scene file (JSON), or the built-in default scene when path is None. `overrides` are "
      "\"key.path=value\" strings as given to --set. Raises lucent.Error naming the file (or TypeError, "
      "ValueError for an override's value, as Scene.set).");
}

}  // namespace lucent::python
