// method.h: the GPU side of a rendering method: what the renderer asks of it each frame. Its description (name,
// parameters, passes, statistics) is data in method_info.h; create_method() builds one from the scene.
// Adding a method: one folder under src/methods/ and one line in method_list.h (see docs/design.md).
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpu/frame_profiler.h"
#include "gpu/gbuffer.h"
#include "lucent/params.h"
#include "lucent/renderer.h"
#include "lucent/scene.h"
#include "methods/method_info.h"
#include "render/scene_gpu.h"
#include "shared/shader_io.h"

namespace lucent::methods {

// What a method is built from. For needs_texture_atlas methods `scene` is the scene as the GPU holds it (each
// translucent mesh replaced by its atlas mesh) and `atlas` its atlas; `precomputed` is what the method's
// PrecomputeDecl computed (from the cache when it could), empty for methods without one. Both stay valid while
// the method lives.
struct MethodSetup {
  const Scene& scene;
  const render::SceneGpu& scene_gpu;
  std::span<const std::byte> precomputed = {};
  const texture_space::SceneAtlas* atlas = nullptr;
};

// What the renderer hands a method each frame. The camera G-buffer is filled and bound (LUCENT_TEX_CAMERA_*),
// the frame block, materials, objects and the frame's counters are bound; the method writes linear radiance into
// `hdr_image` (RGBA32F, LUCENT_IMAGE_HDR) and times its passes with `profiler.pass(name)`, names as declared in
// its MethodInfo.
struct FrameContext {
  const Scene& scene;
  const render::SceneGpu& scene_gpu;
  const gpu::GBuffer& camera_gbuffer;
  GLuint hdr_image;
  gpu::FrameProfiler& profiler;
  bool restart;  // something other than the camera changed: drop accumulated results
  double time_seconds = 0.0;  // animated scenes: the instant the shared geometry was brought to
  std::uint64_t frame = 0;    // the frame's number (FrameRecord::frame when its statistics are read)
};

// One finished frame as the method's statistics() sees it: its pass times and counters.
struct FrameRecord {
  const std::vector<PassTiming>& passes;
  const shader::CountersGPU& counters;
  std::uint64_t frame = 0;  // FrameContext::frame of the frame rendered (read a few frames later)
  double pass_ms(std::string_view name) const {
    for (const PassTiming& p : passes)
      if (p.name == name) return p.ms;
    return 0.0;
  }
  bool ran(std::string_view name) const {
    for (const PassTiming& p : passes)
      if (p.name == name) return true;
    return false;
  }
};

class Method {
 public:
  virtual ~Method() = default;
  // Fills the method's part of the common frame block (restart flag, lights, shading) and its own block,
  // before the frame's passes. `restart`: accumulated results must be dropped.
  virtual void prepare_frame(shader::FrameGPU& frame, bool restart) = 0;
  virtual void render(const FrameContext& context) = 0;
  virtual int accumulated_frames() const = 0;
  // The frame's statistics, as declared in MethodInfo::stats, from what the GPU reported (a few frames late).
  virtual void statistics(const FrameRecord& record, std::vector<FrameStatistic>& out) const = 0;
  virtual std::size_t gpu_memory_bytes() const = 0;  // textures and buffers the method allocated

  // Live changes: the scene's method parameters changed only in parameters declared Live, or its materials
  // changed (same objects, meshes and lights). The new values are in `scene`; return true when the method took
  // them for the next frame, false to be recreated (the default).
  virtual bool update_live_params(const Scene& scene) {
    (void)scene;
    return false;
  }
  virtual bool update_materials(const Scene& scene) {
    (void)scene;
    return false;
  }

  // Diagnostics (after a frame): the scattered radiosity B at surface points, and the virtual point lights.
  // Methods without a radiosity cache or VPLs return empty vectors.
  virtual std::vector<shader::ProbeGPU> scattered_radiosity(std::vector<shader::ProbeGPU> probes) const {
    (void)probes;
    return {};
  }
  virtual std::vector<shader::VplGPU> virtual_point_lights() const { return {}; }
};

// Creates the method the scene names (Scene::method), through the registry of method_list.h.
std::unique_ptr<Method> create_method(const MethodSetup& setup);

}  // namespace lucent::methods
