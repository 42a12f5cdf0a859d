// irradiance_sampler.cpp: see irradiance_sampler.h.
#include "texture_space/irradiance_sampler.h"

#include <algorithm>

#include <fmt/format.h>

#include "gpu/frame_profiler.h"
#include "gpu/gl_debug.h"
#include "lucent/error.h"
#include "render/light_gbuffer.h"
#include "texture_space/texture_gbuffer.h"

namespace lucent::texture_space {
namespace {

GLuint groups(int n, int local) { return static_cast<GLuint>((n + local - 1) / local); }

std::string slot_defines(const SamplerSlots& s) {
  return fmt::format(
      "#define TSIS_IMAGE_SOURCE {}\n#define TSIS_IMAGE_TARGET {}\n#define TSIS_TEX_PYRAMID {}\n"
      "#define TSIS_BINDING_SAMPLES {}\n#define TSIS_BINDING_ROW_CDF {}\n",
      s.source_image, s.target_image, s.pyramid_texture, s.samples_buffer, s.row_cdf_buffer);
}

}  // namespace

IrradianceSampler::IrradianceSampler(int size, const SamplerSlots& slots, const std::string& irradiance_defines)
    : slots_(slots),
      reduce_(gpu::ShaderProgram::compute("texture_space/irradiance_mip_reduce.comp", slot_defines(slots))),
      row_cdf_(gpu::ShaderProgram::compute("texture_space/irradiance_row_cdf.comp", slot_defines(slots))),
      sample_(gpu::ShaderProgram::compute("texture_space/irradiance_sample.comp", slot_defines(slots))) {
  if (!irradiance_defines.empty())
    irradiance_ = gpu::ShaderProgram::compute("texture_space/irradiance.comp", slot_defines(slots) + irradiance_defines);
  while (size_ < size) size_ *= 2, ++levels_;
  glCreateTextures(GL_TEXTURE_2D, 1, &pyramid_);
  glTextureStorage2D(pyramid_, levels_, GL_RGBA32F, size_, size_);
  glTextureParameteri(pyramid_, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  glTextureParameteri(pyramid_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gpu::label_object(GL_TEXTURE, pyramid_, "texture-space E' pyramid");
  glCreateBuffers(1, &samples_);
  glNamedBufferStorage(samples_, 16 + kMaxSamples * static_cast<GLsizeiptr>(sizeof(shader::TsisSampleGPU)), nullptr, 0);
  gpu::label_object(GL_BUFFER, samples_, "texture-space samples");
  glCreateBuffers(1, &row_cdf_buffer_);
  glNamedBufferStorage(row_cdf_buffer_, static_cast<GLsizeiptr>(sizeof(float)) * (static_cast<GLsizeiptr>(size_) * size_ + size_),
                       nullptr, 0);
  gpu::label_object(GL_BUFFER, row_cdf_buffer_, "texture-space row-major CDF");
  clear_level0();
}

IrradianceSampler::~IrradianceSampler() {
  glDeleteTextures(1, &pyramid_);
  glDeleteBuffers(1, &samples_);
  glDeleteBuffers(1, &row_cdf_buffer_);
}

void IrradianceSampler::clear_level0() {
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  glClearTexImage(pyramid_, 0, GL_RGBA, GL_FLOAT, zero);
}

void IrradianceSampler::bind_level0_for_writing() const {
  glBindImageTexture(static_cast<GLuint>(slots_.target_image), pyramid_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
}

void IrradianceSampler::irradiance(int atlas_size) {
  if (irradiance_.id() == 0) throw Error("IrradianceSampler::irradiance: created without irradiance defines");
  bind_level0_for_writing();
  glUseProgram(irradiance_.id());
  glProgramUniform1i(irradiance_.id(), 0, atlas_size);
  glDispatchCompute(groups(atlas_size, 8), groups(atlas_size, 8), 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void IrradianceSampler::build(int order) {
  glUseProgram(reduce_.id());
  for (int level = 1; level < levels_; ++level) {
    glBindImageTexture(static_cast<GLuint>(slots_.source_image), pyramid_, level - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(static_cast<GLuint>(slots_.target_image), pyramid_, level, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    const int n = size_ >> level;
    glDispatchCompute(groups(n, 8), groups(n, 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  if (order == LUCENT_TSIS_ORDER_ROW_MAJOR) {
    glUseProgram(row_cdf_.id());
    glProgramUniform1i(row_cdf_.id(), 0, size_);
    glBindImageTexture(static_cast<GLuint>(slots_.source_image), pyramid_, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(slots_.row_cdf_buffer), row_cdf_buffer_);
    glProgramUniform1i(row_cdf_.id(), 1, 0);  // every row, one invocation each
    glDispatchCompute(groups(size_, 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glProgramUniform1i(row_cdf_.id(), 1, 1);  // the row totals
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

void IrradianceSampler::sample(int n, int order, std::uint32_t seed, std::uint32_t frame, bool write_counters) {
  n = std::clamp(n, 1, kMaxSamples);
  const GLuint p = sample_.id();
  glUseProgram(p);
  glProgramUniform1i(p, 0, n);
  glProgramUniform1i(p, 1, order);
  glProgramUniform1i(p, 2, size_);
  glProgramUniform1i(p, 3, levels_);
  glProgramUniform1ui(p, 4, seed);
  glProgramUniform1ui(p, 5, frame);
  glProgramUniform1i(p, 6, write_counters ? 1 : 0);
  glBindTextureUnit(static_cast<GLuint>(slots_.pyramid_texture), pyramid_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(slots_.samples_buffer), samples_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(slots_.row_cdf_buffer), row_cdf_buffer_);
  glDispatchCompute(groups(n, 64), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void IrradianceSampler::run_stages(const render::LightGBuffer& lights, TextureGBuffer& texture,
                                   const render::SceneGpu& scene_gpu, gpu::FrameProfiler& profiler, int n, int order,
                                   std::uint32_t seed, std::uint32_t frame) {
  lights.render(scene_gpu, profiler);
  {
    auto pass = profiler.pass("texture_gbuffer");
    texture.render(scene_gpu);
  }
  {
    auto pass = profiler.pass("irradiance");
    lights.bind_textures();
    texture.bind_textures();
    irradiance(texture.size());
  }
  {
    auto pass = profiler.pass("mipmaps");
    build(order);
  }
  auto pass = profiler.pass("sampling");
  sample(n, order, seed, frame, true);
}

void IrradianceSampler::bind_samples() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(slots_.samples_buffer), samples_);
}

std::vector<shader::TsisSampleGPU> IrradianceSampler::read_samples(int n, glm::vec4* total) const {
  std::vector<shader::TsisSampleGPU> out(static_cast<std::size_t>(std::clamp(n, 0, kMaxSamples)));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (total) glGetNamedBufferSubData(samples_, 0, 16, total);
  glGetNamedBufferSubData(samples_, 16, static_cast<GLsizeiptr>(out.size() * sizeof(shader::TsisSampleGPU)), out.data());
  return out;
}

std::size_t IrradianceSampler::gpu_memory_bytes() const {
  const std::size_t texels = static_cast<std::size_t>(size_) * static_cast<std::size_t>(size_);
  return texels * 16 * 4 / 3 + 16 + kMaxSamples * sizeof(shader::TsisSampleGPU) + (texels + static_cast<std::size_t>(size_)) * 4;
}

}  // namespace lucent::texture_space
