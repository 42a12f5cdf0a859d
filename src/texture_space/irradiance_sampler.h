// irradiance_sampler.h: stages 1 and 2 of texture-space importance sampling (Chang et al. 2008, Sections 3.1-3.2),
// shared by the methods that use it (texture-space-is, hybrid): E' = (A_S / A_T) F_t E per atlas texel into level
// 0 of a sum pyramid (RGBA32F; a = mean of the bands, the sampled density), the pyramid's upper levels, and N
// texels drawn with probability E'_a(texel) / E'_total,a by the inverse CDF in mipmap order (Fig. 2b: one top-down
// descent per sample, shared/mip_sampling.h) or in row-major order (Fig. 2a: binary searches over the row totals
// and within the row). The binding slots are the using method's own (SamplerSlots, from its _io.h); texels
// outside the caller's size stay 0. Shaders: shaders/texture_space/irradiance*.comp; samples: shared/tsis_samples.h.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/shader_program.h"
#include "shared/tsis_samples.h"

namespace lucent::gpu { class FrameProfiler; }
namespace lucent::render { class LightGBuffer; class SceneGpu; }

namespace lucent::texture_space {

class TextureGBuffer;

// The inverse-CDF order named by a method's `order` parameter: "row-major" (Fig. 2a), else mipmap (Fig. 2b).
inline int sampling_order(std::string_view name) {
  return name == "row-major" ? LUCENT_TSIS_ORDER_ROW_MAJOR : LUCENT_TSIS_ORDER_MIPMAP;
}

// The slots the sampler's passes bind, inside the using method's ranges of shared/bindings.h.
struct SamplerSlots {
  int source_image;    // RGBA32F: pyramid level read (reduction, row CDF)
  int target_image;    // RGBA32F: pyramid level written (irradiance: level 0)
  int pyramid_texture; // the pyramid with all its levels (sampling)
  int samples_buffer;  // vec4 total, then TsisSampleGPU[] (std430)
  int row_cdf_buffer;  // float[P * P + P] (std430): the row-major CDF
};

class IrradianceSampler {
 public:
  static constexpr int kMaxSamples = 4096;
  // `size`: width = height of the E' image; the pyramid is the next power of two P >= size.
  // `irradiance_defines`: what shaders/texture_space/irradiance.comp needs besides the slots (light sampling,
  // TSIS_TEX_POSITION and TSIS_TEX_NORMAL_RATIO: the texture G-buffer's units); empty: no irradiance pass.
  IrradianceSampler(int size, const SamplerSlots& slots, const std::string& irradiance_defines = "");
  ~IrradianceSampler();
  IrradianceSampler(const IrradianceSampler&) = delete;
  IrradianceSampler& operator=(const IrradianceSampler&) = delete;

  int pyramid_size() const { return size_; }
  int levels() const { return levels_; }
  GLuint pyramid() const { return pyramid_; }
  void clear_level0();
  void bind_level0_for_writing() const;
  // Stage 1 into level 0 for an atlas of `atlas_size` texels; the caller has bound the frame's light and texture
  // G-buffer textures. Counts the lit texels into the frame's counters (method_counts[0]).
  void irradiance(int atlas_size);
  // The pyramid's upper levels from level 0, and the row CDF when `order` is row-major.
  void build(int order);
  // Draws `n` (1..kMaxSamples) samples with seeds (seed, frame); `write_counters`: the total also goes to the
  // frame's counters (method_counts[1], float bits).
  void sample(int n, int order, std::uint32_t seed, std::uint32_t frame, bool write_counters);
  // A frame's stages 1-2 as the methods run them, each timed as a pass: the light G-buffer ("light_gbuffer"), the
  // texture G-buffer redrawn ("texture_gbuffer", so deforming meshes follow), irradiance(), build() ("mipmaps")
  // and sample() with the counters ("sampling").
  void run_stages(const render::LightGBuffer& lights, TextureGBuffer& texture, const render::SceneGpu& scene_gpu,
                  gpu::FrameProfiler& profiler, int n, int order, std::uint32_t seed, std::uint32_t frame);
  void bind_samples() const;
  // Tests and tools: the samples of the last sample() and the total (E'_total per band, a the sampled total).
  std::vector<shader::TsisSampleGPU> read_samples(int n, glm::vec4* total = nullptr) const;
  std::size_t gpu_memory_bytes() const;

 private:
  int size_ = 1, levels_ = 1;
  SamplerSlots slots_;
  gpu::ShaderProgram reduce_, row_cdf_, sample_, irradiance_;
  GLuint pyramid_ = 0, samples_ = 0, row_cdf_buffer_ = 0;
};

}  // namespace lucent::texture_space
