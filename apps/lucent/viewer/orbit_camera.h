// orbit_camera.h: the viewer's camera controls: orbit about the target, pan, zoom (dolly), reset, and the
// readout of the camera as scene-file JSON. Pure math on lucent::Camera (no GL), unit-tested on the CPU.
//
// The camera is edited in place (eye rotated about the target), never rebuilt from angles, so a camera the
// user has not moved is bit-for-bit the scene file's: the viewer's image equals `lucent render`'s.
#pragma once
#include <string>

#include "lucent/scene.h"

namespace lucent::viewer {

class OrbitCamera {
 public:
  explicit OrbitCamera(const Camera& home = {}) : home_(home), camera_(home) {}

  // Mouse motion in pixels over a view `view_height` pixels tall.
  void orbit(float dx_pixels, float dy_pixels);                    // drag: 180 degrees per view height
  void pan(float dx_pixels, float dy_pixels, float view_height);   // the point under the cursor follows it
  void zoom(float wheel_steps);                                    // each step: 10% closer (positive) or farther
  void reset() { camera_ = home_; }
  void set_home(const Camera& home) { home_ = camera_ = home; }
  void set_fov(float fov_y_deg) { camera_.fov_y_deg = fov_y_deg; }

  const Camera& camera() const { return camera_; }
  const Camera& home() const { return home_; }
  bool moved() const;
  float distance() const;  // eye to target [scene units]

 private:
  Camera home_;
  Camera camera_;
};

// `"camera": {"eye": [...], "target": [...], "up": [...], "fov_y_deg": ...}` with enough digits that the scene
// loader reads back the same floats, for pasting into a scene file.
std::string camera_readout(const Camera& camera);

}  // namespace lucent::viewer
