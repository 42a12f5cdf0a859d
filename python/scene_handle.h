// scene_handle.h: lucent.Scene: a scene file (or the built-in default scene) with its overrides, the
// "key.path=value" assignments of the CLI's --set, and the scene they give. Renders and references apply
// further overrides (size, frames, method) to a copy.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "lucent/scene.h"

namespace lucent::python {

struct SceneHandle {
  std::optional<std::string> path;     // none: the built-in default scene
  std::vector<std::string> overrides;  // "key.path=value", applied in order
  Scene scene;                         // the file with the overrides applied

  SceneHandle(std::optional<std::string> path, std::vector<std::string> overrides);
  // The scene with `extra` overrides after this handle's own; throws lucent::Error as load_scene does.
  Scene with(const std::vector<std::string>& extra) const;
};

// `scene.set(key, value)`: the override "key=<value as JSON>"; the scene is parsed again at once, so a bad key or
// value raises (TypeError, ValueError or lucent.Error, as Scene.set documents) and leaves the handle as it was.
SceneHandle& set_value(SceneHandle& handle, const std::string& key, const pybind11::handle& value);

}  // namespace lucent::python
