// irradiance_sampler.h: stage 2 of texture-space importance sampling (Chang et al. 2008, Section 3.2): the sum
// pyramid of the E' image (RGBA32F; a = mean of the bands, the sampled density) and N texels drawn with
// probability E'_a(texel) / E'_total,a by the inverse CDF in mipmap order (Fig. 2b: one top-down descent per
// sample, shared/mip_sampling.h) or in row-major order (Fig. 2a: binary searches over the row totals and within
// the row). Level 0 is written by the caller (image unit LUCENT_IMAGE_TSIS_TARGET, bind_level0_for_writing);
// texels outside the caller's size stay 0. Shaders: shaders/mip_reduce.comp, row_cdf.comp, sample.comp.
#pragma once
#include <cstdint>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/shader_program.h"
#include "methods/texture_space_is/texture_space_is_io.h"

namespace lucent::methods {

class IrradianceSampler {
 public:
  static constexpr int kMaxSamples = 4096;
  // `size`: width = height of the E' image; the pyramid is the next power of two P >= size.
  explicit IrradianceSampler(int size);
  ~IrradianceSampler();
  IrradianceSampler(const IrradianceSampler&) = delete;
  IrradianceSampler& operator=(const IrradianceSampler&) = delete;

  int pyramid_size() const { return size_; }
  int levels() const { return levels_; }
  GLuint pyramid() const { return pyramid_; }
  void clear_level0();
  void bind_level0_for_writing() const;
  // The pyramid's upper levels from level 0, and the row CDF when `order` is row-major.
  void build(int order);
  // Draws `n` (1..kMaxSamples) samples with seeds (seed, frame); `write_counters`: the total also goes to the
  // frame's counters (method_counts[1], float bits).
  void sample(int n, int order, std::uint32_t seed, std::uint32_t frame, bool write_counters);
  void bind_samples() const;
  // Tests and tools: the samples of the last sample() and the total (E'_total per band, a the sampled total).
  std::vector<shader::TsisSampleGPU> read_samples(int n, glm::vec4* total = nullptr) const;
  std::size_t gpu_memory_bytes() const;

 private:
  int size_ = 1, levels_ = 1;
  gpu::ShaderProgram reduce_, row_cdf_, sample_;
  GLuint pyramid_ = 0, samples_ = 0, row_cdf_buffer_ = 0;
};

}  // namespace lucent::methods
