// denoiser.cpp: the denoising stage's textures and passes (the math is in shaders/denoise/).
#include "denoise/denoiser.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "denoise/denoise_io.h"
#include "gpu/gl_debug.h"
#include "gpu/image_texture.h"

namespace lucent::denoise {
namespace {

void dispatch(const gpu::ShaderProgram& program, int width, int height) {
  glUseProgram(program.id());
  glDispatchCompute(static_cast<GLuint>((width + 7) / 8), static_cast<GLuint>((height + 7) / 8), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

std::string defines(bool material_maps) { return material_maps ? "#define LUCENT_MATERIAL_MAPS 1\n" : ""; }

}  // namespace

Denoiser::Denoiser(bool material_maps)
    : material_maps_(material_maps),
      temporal_(gpu::ShaderProgram::compute("denoise/temporal.comp", defines(material_maps))),
      variance_(gpu::ShaderProgram::compute("denoise/variance.comp", defines(material_maps))),
      atrous_(gpu::ShaderProgram::compute("denoise/atrous.comp", defines(material_maps))),
      modulate_(gpu::ShaderProgram::compute("denoise/modulate.comp", defines(material_maps))) {
  glCreateBuffers(1, &block_);
  glNamedBufferStorage(block_, sizeof(shader::DenoiseGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
  gpu::label_object(GL_BUFFER, block_, "denoise");
}

Denoiser::~Denoiser() {
  release();
  glDeleteBuffers(1, &block_);
}

void Denoiser::release() {
  GLuint textures[] = {frozen_,    combined_[0],      combined_[1],       moments_[0],     moments_[1],
                       filter_[0], filter_[1], previous_average_, previous_position_, previous_normal_};
  glDeleteTextures(10, textures);
  frozen_ = combined_[0] = combined_[1] = moments_[0] = moments_[1] = filter_[0] = filter_[1] = 0;
  previous_average_ = previous_position_ = previous_normal_ = 0;
  width_ = height_ = 0;
  has_previous_ = false;
}

void Denoiser::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  release();
  width_ = width, height_ = height;
  frozen_ = gpu::make_image_texture(width, height, GL_RGBA32F, "denoise: kept history");
  combined_[0] = gpu::make_image_texture(width, height, GL_RGBA32F, "denoise: combined estimate A");
  combined_[1] = gpu::make_image_texture(width, height, GL_RGBA32F, "denoise: combined estimate B");
  moments_[0] = gpu::make_image_texture(width, height, GL_RGBA32F, "denoise: moments A");
  moments_[1] = gpu::make_image_texture(width, height, GL_RGBA32F, "denoise: moments B");
  previous_average_ = gpu::make_image_texture(width, height, GL_RGBA32F, "denoise: the method's previous average");
  filter_[0] = gpu::make_image_texture(width, height, GL_RGBA32F, "denoise: wavelet A");
  filter_[1] = gpu::make_image_texture(width, height, GL_RGBA32F, "denoise: wavelet B");
  previous_position_ = gpu::make_image_texture(width, height, GL_RGBA32F, "denoise: previous position");
  previous_normal_ = gpu::make_image_texture(width, height, GL_RGBA16F, "denoise: previous normal");
}

std::size_t Denoiser::gpu_memory_bytes() const {
  return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * (9 * 16 + 8);
}

void Denoiser::run(const DenoiseFrame& in) {
  const int width = in.frame.output_size.x, height = in.frame.output_size.y;
  const DenoiseSettings& s = in.settings;
  const bool resized = width != width_ || height != height_;
  resize(width, height);

  shader::DenoiseGPU block{};
  block.previous_clip_from_world = previous_clip_from_world_;
  block.weights = glm::vec4(s.sigma_luminance, s.normal_power, s.sigma_plane,
                            2.0f * std::tan(glm::radians(in.fov_y_deg) * 0.5f) / static_cast<float>(height));
  const double method_frames = std::max(in.method_frames, 1);
  // An edit (or a new size) drops the history; any other restart of the method's average (a camera move, or a
  // method that gives a fresh estimate each frame) keeps it, reprojected (through the identity when the camera
  // stayed: then the stage averages the method's frames itself).
  int state = LUCENT_DENOISE_KEEP;
  if (in.edited || resized || !has_previous_) state = LUCENT_DENOISE_DROP;
  else if (in.method_restarted) state = LUCENT_DENOISE_REPROJECT;
  if (state == LUCENT_DENOISE_REPROJECT)
    kept_frames_ = std::min(history_frames_, static_cast<double>(s.history_frames));
  else if (state == LUCENT_DENOISE_DROP)
    kept_frames_ = 0.0;
  history_frames_ = kept_frames_ + method_frames;
  block.history = glm::vec4(static_cast<float>(s.history_frames), static_cast<float>(method_frames), s.fade_frames, 1.0f);
  block.state = glm::ivec4(state, 0, 0, 0);
  glNamedBufferSubData(block_, 0, sizeof(block), &block);
  glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_DENOISE, block_);
  in.camera_gbuffer.bind_textures(LUCENT_TEX_CAMERA_POSITION, LUCENT_TEX_CAMERA_NORMAL, LUCENT_TEX_CAMERA_DEPTH);

  const int previous = current_;
  current_ = 1 - current_;
  {
    auto pass = in.profiler.pass("denoise_temporal");
    glBindTextureUnit(LUCENT_TEX_DENOISE_INPUT, in.radiance);
    glBindTextureUnit(LUCENT_TEX_DENOISE_HISTORY, combined_[previous]);
    glBindTextureUnit(LUCENT_TEX_DENOISE_PREVIOUS_POSITION, previous_position_);
    glBindTextureUnit(LUCENT_TEX_DENOISE_PREVIOUS_NORMAL, previous_normal_);
    glBindTextureUnit(LUCENT_TEX_DENOISE_PREVIOUS_AVERAGE, previous_average_);
    glBindTextureUnit(LUCENT_TEX_DENOISE_PREVIOUS_MOMENTS, moments_[previous]);
    glBindImageTexture(LUCENT_IMAGE_DENOISE_FROZEN, frozen_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindImageTexture(LUCENT_IMAGE_DENOISE_OUTPUT, combined_[current_], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(LUCENT_IMAGE_DENOISE_MOMENTS, moments_[current_], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    dispatch(temporal_, width, height);
    // The method's average as the next frame's previous one, before the result overwrites it.
    glCopyImageSubData(in.radiance, GL_TEXTURE_2D, 0, 0, 0, 0, previous_average_, GL_TEXTURE_2D, 0, 0, 0, 0, width,
                       height, 1);
  }
  {
    auto pass = in.profiler.pass("denoise_filter");
    glBindTextureUnit(LUCENT_TEX_DENOISE_COMBINED, combined_[current_]);
    glBindTextureUnit(LUCENT_TEX_DENOISE_MOMENTS, moments_[current_]);
    glBindImageTexture(LUCENT_IMAGE_DENOISE_OUTPUT, filter_[0], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    dispatch(variance_, width, height);
    for (int k = 0; k < s.iterations; ++k) {
      block.history.w = static_cast<float>(1 << k);
      block.state.y = k;
      glNamedBufferSubData(block_, 0, sizeof(block), &block);
      glBindTextureUnit(LUCENT_TEX_DENOISE_FILTER, filter_[k % 2]);
      glBindImageTexture(LUCENT_IMAGE_DENOISE_OUTPUT, filter_[(k + 1) % 2], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
      dispatch(atrous_, width, height);
    }
  }
  {
    auto pass = in.profiler.pass("denoise_modulate");
    glBindTextureUnit(LUCENT_TEX_DENOISE_FILTER, filter_[s.iterations % 2]);
    glBindTextureUnit(LUCENT_TEX_DENOISE_COMBINED, combined_[current_]);
    glBindImageTexture(LUCENT_IMAGE_DENOISE_OUTPUT, in.radiance, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    dispatch(modulate_, width, height);
  }
  // This frame's camera and G-buffer become the next frame's previous ones.
  glCopyImageSubData(in.camera_gbuffer.position(), GL_TEXTURE_2D, 0, 0, 0, 0, previous_position_, GL_TEXTURE_2D, 0, 0, 0,
                     0, width, height, 1);
  glCopyImageSubData(in.camera_gbuffer.normal(), GL_TEXTURE_2D, 0, 0, 0, 0, previous_normal_, GL_TEXTURE_2D, 0, 0, 0, 0,
                     width, height, 1);
  previous_clip_from_world_ = in.frame.clip_from_world;
  has_previous_ = true;
}

}  // namespace lucent::denoise
