// light_gbuffer.h: step 1 shared by the methods that sample light space (radiosity-maps, per-pixel): the lights
// as the GPU sees them, the layered light G-buffer (render/light_views.h) and the pass that renders it.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

#include "gpu/gbuffer.h"
#include "gpu/frame_profiler.h"
#include "gpu/layer_views.h"
#include "gpu/shader_program.h"
#include "render/light_views.h"

namespace lucent::render {

// Preprocessor defines for shaders that include common/light_sampling.glsl or bssrdf/model.h: the point-light path
// is compiled only when the scene has point or spot lights, the tabulated model only when a material uses it.
std::string light_sampling_defines(const Scene& scene);
// The shader loop iterations of one S_d evaluation of light_sampling.glsl: 1, or 1 + kPhotonBeamSamples when a
// translucent object uses photon beam diffusion (its beam integral is a loop), so that a method can count the
// iterations an invocation runs against llvmpipe's loop cap (platform::check_loop_iterations).
std::uint64_t light_sampling_iterations_per_sample(const Scene& scene);
// One invocation of scattered_radiosity (light_sampling.glsl) samples N per band and light in one loop nest, each
// sample `iterations_per_sample` loop iterations: refused on llvmpipe, with one line naming `method` and the N that
// fits, when that passes the driver's loop budget, which would end the loops early and darken the image.
void check_light_sampling_loops(std::string_view method, int lights, std::uint64_t N,
                                std::uint64_t iterations_per_sample);

class LightGBuffer {
 public:
  LightGBuffer(const Scene& scene, const SceneGpu& scene_gpu, int size);

  // Fills the frame block's lights, light views and light counts (light_counts.xyz); the shadow taps
  // (light_counts.w) are the method's.
  void fill_frame(shader::FrameGPU& frame) const;
  // Renders every light layer in one layered pass (pass "light_gbuffer").
  void render(const SceneGpu& scene_gpu, gpu::FrameProfiler& profiler) const;
  // Binds position, normal and depth to LUCENT_TEX_LIGHT_*.
  void bind_textures() const;

  int light_count() const { return static_cast<int>(views_.lights.size()); }
  int size() const { return size_; }
  const LightViews& views() const { return views_; }
  std::size_t gpu_memory_bytes() const;

 private:
  int size_;
  LightViews views_;
  gpu::GBuffer gbuffer_;
  gpu::LayerViews layer_views_;
  gpu::ShaderProgram program_;
};

}  // namespace lucent::render
