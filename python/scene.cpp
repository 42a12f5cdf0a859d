// scene.cpp: lucent.load_scene and lucent.Scene.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "scene_handle.h"

namespace lucent::python {
namespace {

Scene load(const std::optional<std::string>& path, const std::vector<std::string>& overrides) {
  return path ? load_scene(*path, overrides) : default_scene(overrides);
}

py::object param_value(const ParamValue& value) {
  return std::visit(
      [](const auto& v) -> py::object {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, glm::vec3>) {
          return py::make_tuple(v.x, v.y, v.z);
        } else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) {
          py::list list;
          for (const glm::vec3& p : v) list.append(py::make_tuple(p.x, p.y, p.z));
          return list;
        } else {
          return py::cast(v);
        }
      },
      value);
}

py::dict params_dict(const ParamValues& values) {
  py::dict dict;
  for (const auto& [name, value] : values.all()) dict[py::str(name)] = param_value(value);
  return dict;
}

// `scene.set(key, value)`: the override "key=<value as JSON>"; the scene is parsed again at once, so a bad key or
// value raises here and leaves the scene as it was.
SceneHandle& set(SceneHandle& handle, const std::string& key, const py::handle& value) {
  std::vector<std::string> overrides = handle.overrides;
  overrides.push_back(fmt::format("{}={}", key, to_json_text(value)));
  handle.scene = load(handle.path, overrides);
  handle.overrides = std::move(overrides);
  return handle;
}

std::vector<std::string> object_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const SceneObject& object : scene.objects) names.push_back(object.name);
  return names;
}

}  // namespace

SceneHandle::SceneHandle(std::optional<std::string> path_, std::vector<std::string> overrides_)
    : path(std::move(path_)), overrides(std::move(overrides_)), scene(load(path, overrides)) {}

Scene SceneHandle::with(const std::vector<std::string>& extra) const {
  std::vector<std::string> all = overrides;
  all.insert(all.end(), extra.begin(), extra.end());
  return load(path, all);
}

void bind_scene(py::module_& m) {
  py::class_<SceneHandle>(m, "Scene", "A scene file (or the built-in default scene) with --set style overrides.")
      .def_readonly("path", &SceneHandle::path, "the scene file; None for the built-in default scene")
      .def_readonly("overrides", &SceneHandle::overrides, "the \"key.path=value\" overrides, in order")
      .def("set", &set, py::arg("key"), py::arg("value"), py::return_value_policy::reference,
           "Overrides a scene value as `lucent render --set key=value` does (value: a number, string, bool, "
           "list, dict or numpy array, written as JSON), e.g. set(\"objects.0.material\", \"Marble\"), "
           "set(\"method.K\", 8). Raises lucent.Error and keeps the scene as it was when the result is invalid. "
           "Returns the scene.")
      .def_property_readonly("source", [](const SceneHandle& h) { return h.scene.source; })
      .def_property_readonly("method", [](const SceneHandle& h) { return h.scene.method; })
      .def_property_readonly("method_params", [](const SceneHandle& h) { return params_dict(h.scene.method_params); },
                             "the method's parameters, every declared one (defaults filled in)")
      .def_property_readonly("width", [](const SceneHandle& h) { return h.scene.render.width; })
      .def_property_readonly("height", [](const SceneHandle& h) { return h.scene.render.height; })
      .def_property_readonly("frames", [](const SceneHandle& h) { return h.scene.render.frames; })
      .def_property_readonly("seed", [](const SceneHandle& h) { return h.scene.render.seed; })
      .def_property_readonly("scale_mm", [](const SceneHandle& h) { return h.scene.scale_mm; },
                             "millimetres per scene unit")
      .def_property_readonly("objects", [](const SceneHandle& h) { return object_names(h.scene); },
                             "the objects' names, in order (objects.<index> in overrides)")
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
      "\"key.path=value\" strings as given to --set. Raises lucent.Error with the CLI's message.");
}

}  // namespace lucent::python
