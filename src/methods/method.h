// method.h: the interface every rendering method implements, and the registry that names them.
// Adding a method: one folder under src/methods/, one entry in method_registry.cpp.
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "gpu/gbuffer.h"
#include "gpu/gpu_timer.h"
#include "lucent/params.h"
#include "lucent/scene.h"
#include "render/scene_gpu.h"
#include "shared/shader_io.h"

namespace lucent::methods {

// What the renderer hands a method each frame. The camera G-buffer is filled and bound; the method writes
// linear radiance into `hdr_image` (RGBA32F, bound as LUCENT_IMAGE_HDR).
struct FrameContext {
  const Scene& scene;
  const render::SceneGpu& scene_gpu;
  const gpu::GBuffer& camera_gbuffer;
  GLuint hdr_image;
  gpu::GpuTimer& timer;
  bool restart;  // something other than the camera changed: drop accumulated results
};

class Method {
 public:
  virtual ~Method() = default;
  // Fills the method's part of the frame block (views, counts, biases) before it is uploaded.
  virtual void prepare_frame(shader::FrameGPU& frame, bool restart) = 0;
  virtual void render(const FrameContext& context) = 0;
  virtual int accumulated_frames() const = 0;
  virtual std::uint64_t bssrdf_samples_last_frame() const = 0;
  virtual std::size_t gpu_memory_bytes() const = 0;  // textures and buffers the method allocated
  // Last frame: camera pixels on translucent objects, and of those the ones the method has radiosity for.
  virtual glm::uvec2 pixel_coverage() const = 0;
  // Diagnostics (after a frame): the scattered radiosity B at surface points, and the virtual point lights.
  // Methods without a radiosity cache or VPLs return empty vectors.
  virtual std::vector<shader::ProbeGPU> scattered_radiosity(std::vector<shader::ProbeGPU> probes) const {
    (void)probes;
    return {};
  }
  virtual std::vector<shader::VplGPU> virtual_point_lights() const { return {}; }
};

struct MethodInfo {
  std::string_view name;
  std::string_view summary;
  std::span<const ParamDecl> params;
  std::unique_ptr<Method> (*create)(const Scene& scene, const render::SceneGpu& scene_gpu);
};

std::span<const MethodInfo> method_registry();
const MethodInfo* find_method(std::string_view name);

}  // namespace lucent::methods
