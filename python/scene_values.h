// scene_values.h: a scene read back as Python values, typed as declared (an Int parameter is an int, not 16.0):
// method parameters, objects with their materials, lights (docs/python.md, "Reading and editing a scene").
#pragma once
#include <pybind11/pybind11.h>

#include "lucent/scene.h"

namespace lucent::python {

// {name: value} of every parameter of the scene's method, typed by its declaration.
pybind11::dict method_params_dict(const Scene& scene);
// lucent.SceneItems of lucent.SceneObject, by index or name.
pybind11::object objects_of(const Scene& scene);
// lucent.SceneItems of dicts: directional lights, then point and spot lights, then an environment's samples.
pybind11::object lights_of(const Scene& scene);

// {"eye", "target", "up", "fov_y_deg"}.
// eye and target in the scene file's coordinates (Scene::origin added back).
pybind11::dict camera_dict(const Camera& camera, const glm::dvec3& origin);
// "aces", "reinhard" or "linear" (render.tonemap).
const char* tonemap_name(ToneMapOperator op);
// A float as the shortest decimal that reads back as it (0.0024, not 0.002400000113993883), as the scene file wrote it.
double decimal(float x);

void bind_scene_values(pybind11::module_& m);  // SceneItems, SceneObject

}  // namespace lucent::python
