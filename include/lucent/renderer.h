// renderer.h: renders a scene with one of lucent's methods into the application's own framebuffer.
//
//   auto context = lucent::create_headless_context();        // or the application's own GL 4.5 context
//   lucent::Renderer renderer(lucent::load_scene("bunny.json"));
//   renderer.render(camera, {fbo, width, height});          // progressive while only the camera moves
//   renderer.timings();                                     // per-step GPU milliseconds
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "lucent/image.h"
#include "lucent/scene.h"

namespace lucent {

// Where a frame goes: a framebuffer object of the application (0 = the default framebuffer).
struct RenderTarget {
  unsigned framebuffer = 0;
  int width = 0;
  int height = 0;
};

struct PassTiming {
  std::string name;  // a pass name as the method declares it (`lucent methods`); also the GL debug group name
  double ms = 0.0;   // GPU time from timer queries
};

// A named value a method (or the renderer) reports for a frame: samples drawn, pixels covered, ...
struct FrameStatistic {
  std::string name;
  double value = 0.0;
  std::string unit;  // "" for counts and fractions
};

// What one frame cost and what it did, as the GPU reported it (read back a few frames after the frame, so that
// rendering never waits for the GPU; see Renderer::timings() and Renderer::finished_frames()).
struct FrameTimings {
  std::uint64_t frame = 0;          // 1 for the renderer's first frame; 0 before any frame has come back
  std::vector<PassTiming> passes;   // in submission order: the renderer's (camera_gbuffer, tonemap), animated
                                    // geometry's and the method's own
  double total_ms = 0.0;            // sum of the passes
  std::vector<FrameStatistic> stats;  // the renderer's (translucent_pixels, coverage, gpu_memory_mb) and the method's
  std::size_t gpu_memory_bytes = 0;   // textures and buffers of the method and the output images

  // The statistic's value, or `fallback` when the frame did not report it.
  double stat(std::string_view name, double fallback = 0.0) const;
  double pass_ms(std::string_view name) const;  // 0 when the frame did not run the pass
};

// A virtual point light carrying a translucent object's emergent light to the scene (radiosity-maps, VPLs on).
struct VirtualPointLight {
  glm::vec3 position{0.0f};   // [scene units]
  glm::vec3 normal{0.0f};     // outward unit normal
  float area = 0.0f;          // surface area it stands for [scene units^2]; 0 when its direction missed the object
  glm::vec3 radiosity{0.0f};  // scattered radiosity B at its position (before the exit Fresnel term)
  float eta = 1.0f;           // relative refractive index of its material
};

// Progress of the CPU work a method needs before its first frame (texture-space methods' atlas, a method's
// precomputation): `step` names the work ("texture atlas", or the method's precompute kind), `fraction` runs from
// 0 to 1 within a step (non-decreasing, 1 last; at once when the precompute cache had it). Called on the thread
// that constructs the renderer or calls scene_changed(). Methods that precompute nothing never call it. It may throw
// to abandon the work (an application's cancel button): the exception leaves the constructor or scene_changed().
using RenderProgress = std::function<void(std::string_view step, double fraction)>;

class Renderer {
 public:
  // Needs a current OpenGL 4.5 core context. Compiles shaders and uploads the scene; throws lucent::Error.
  // `progress` (may be empty) hears of the precomputation, here and in later rebuilds (scene_changed()).
  explicit Renderer(Scene scene, RenderProgress progress = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders one frame seen by `camera` into `target`, tone-mapped. Accumulates with previous frames unless
  // something other than the camera changed since (see scene_changed()).
  void render(const Camera& camera, const RenderTarget& target);

  // The scene, for changes: call scene_changed() after editing lights, materials, geometry or parameters. When it
  // throws (a scene that does not build), nothing is built: render() throws until a scene_changed() succeeds (put
  // the last good scene back and call it again: it rebuilds).
  Scene& scene();
  const Scene& scene() const;
  void scene_changed();
  // Animation time: deforming objects and blob surfaces take their shape at t for the next frame (which then
  // restarts accumulation). No effect on static scenes.
  void set_time(double seconds);
  double time() const;

  // Drops the accumulated frames and whatever the method cached from the scene (voxel-paths' solved volume),
  // so the next frame computes everything again, as after a scene change but without rebuilding (benchmarks of
  // a method's full per-frame cost use it).
  void restart();

  int accumulated_frames() const;
  // The newest frame the GPU has finished and reported: never waits, so it is usually a few frames behind the
  // last render() (see FrameTimings::frame).
  const FrameTimings& timings() const;
  // Every frame reported since the last call, oldest first. wait = true first waits for the frames in flight,
  // so that the last entry is the last frame rendered (offline tools, tests).
  std::vector<FrameTimings> finished_frames(bool wait);
  // Waits for the last rendered frame and returns its timings.
  const FrameTimings& last_frame_timings();
  std::string device() const;           // GL renderer and version
  static std::string device_of_current_context();

  // Diagnostics of the last frame, for methods that cache scattered radiosity (empty otherwise):
  // B at surface points (position, outward normal; w = 1 where a map sees the point, else 0), and the VPLs.
  std::vector<glm::vec4> scattered_radiosity(const std::vector<glm::vec3>& points,
                                             const std::vector<glm::vec3>& normals) const;
  std::vector<VirtualPointLight> virtual_point_lights() const;

  // The last frame's linear radiance and tone-mapped image, top row first.
  ImageRGBA32F read_radiance() const;
  ImageRGBA8 read_display() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lucent
