// default_scene.cpp: the built-in scene `lucent render` uses without a scene file: a potato torus and a marble
// sphere on a diffuse floor, lit from behind and above so that light visibly bleeds through.
#include "lucent/scene.h"

namespace lucent {

const char* default_scene_json() {
  return R"json({
  "comment": "lucent's built-in default scene (procedural; no external files)",
  "scale_mm": 10.0,
  "camera": { "eye": [0.0, 1.6, 5.2], "target": [0.0, 0.55, 0.0], "fov_y_deg": 38 },
  "lights": [
    { "direction": [0.8, -0.45, -0.25], "radiance": [3.2, 3.0, 2.8] }
  ],
  "objects": [
    { "name": "torus", "shape": "torus", "major_radius": 0.9, "minor_radius": 0.38,
      "translate": [-0.75, 0.9, -0.3], "rotate_deg": [70, 0, 20], "material": "Potato" },
    { "name": "sphere", "shape": "sphere", "radius": 0.6, "translate": [1.05, 0.6, 0.3], "material": "Marble" },
    { "name": "floor", "shape": "plane", "extent": [12, 12], "albedo": [0.55, 0.55, 0.58] }
  ],
  "method": { "name": "radiosity-maps", "K": 16, "N": 32 },
  "render": { "width": 640, "height": 400, "frames": 8, "background": [0.08, 0.09, 0.11] }
})json";
}

Scene default_scene(const std::vector<std::string>& overrides) {
  return parse_scene(default_scene_json(), "<built-in default scene>", ".", overrides);
}

}  // namespace lucent
