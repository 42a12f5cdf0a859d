// scene_handle.h: lucent.Scene: a scene file (or the built-in default scene) with its overrides, the
// "key.path=value" assignments of the CLI's --set, and the scene they give. Renders and references apply
// further overrides (size, frames, method) to a copy.
#pragma once
#include <optional>
#include <string>
#include <vector>

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

}  // namespace lucent::python
