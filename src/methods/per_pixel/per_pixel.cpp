// per_pixel.cpp: see per_pixel.h.
#include "methods/per_pixel/per_pixel.h"

#include <cstring>

#include "gpu/frame_counters.h"
#include "gpu/gl_debug.h"
#include "gpu/shader_program.h"
#include "render/light_gbuffer.h"

namespace lucent::methods {
namespace {

constexpr ParamDecl kParams[] = {
    {"N", ParamType::Int, "32", "samples", 1, 65536, "", "samples per colour band per pixel per frame"},
    {"light_map_size", ParamType::Int, "512", "texels", 8, 8192, "", "resolution of each light G-buffer layer"},
    {"visibility_taps", ParamType::Int, "3", "taps/axis", 1, 7, "", "multi-sampled shadow taps per axis"},
    {"progressive", ParamType::Bool, "true", "", 0, 1, "", "accumulate while nothing (camera included) changes"},
    {"specular", ParamType::Bool, "true", "", 0, 1, "", "add GGX specular reflection of the lights"},
    {"roughness", ParamType::Float, "0.15", "GGX alpha", 0.01, 1, "", "roughness of the specular reflection"},
};

class PerPixel final : public Method {
 public:
  PerPixel(const Scene& scene, const render::SceneGpu& scene_gpu)
      : params_(scene.method_params),
        light_gbuffer_(scene, scene_gpu, params_.integer("light_map_size")),
        program_(gpu::ShaderProgram::compute("per_pixel/shade.comp", render::light_sampling_defines(scene))) {}
  ~PerPixel() override { glDeleteTextures(1, &accumulated_); }

  void prepare_frame(shader::FrameGPU& frame, bool restart) override {
    // View dependent: a camera change restarts accumulation too.
    bool camera_moved = std::memcmp(&frame.clip_from_world, &last_camera_, sizeof(last_camera_)) != 0;
    last_camera_ = frame.clip_from_world;
    restart = restart || camera_moved || !params_.boolean("progressive") || frame.sizes.z != width_ ||
              frame.sizes.w != height_;
    accumulated_frames_ = restart ? 1 : accumulated_frames_ + 1;
    frame.counts = glm::ivec4(0, 0, params_.integer("N"), params_.integer("visibility_taps"));
    light_gbuffer_.fill_frame(frame);
    frame.seeds.z = restart ? 1u : 0u;
    frame.biases.w = static_cast<float>(params_.number("roughness"));
    frame.options.z = params_.boolean("specular") ? 1.0f : 0.0f;
    if (frame.sizes.z != width_ || frame.sizes.w != height_) resize(frame.sizes.z, frame.sizes.w);
  }

  void render(const FrameContext& context) override {
    light_gbuffer_.render(context.scene_gpu, context.timer);
    gpu::DebugGroup group("per_pixel");
    context.timer.begin("per_pixel");
    counters_.reset_and_bind();
    light_gbuffer_.bind_textures();
    glBindImageTexture(LUCENT_IMAGE_RADIOSITY, accumulated_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUseProgram(program_.id());
    glDispatchCompute(static_cast<GLuint>((width_ + 7) / 8), static_cast<GLuint>((height_ + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    context.timer.end();
  }

  int accumulated_frames() const override { return accumulated_frames_; }
  glm::uvec2 pixel_coverage() const override {
    shader::CountersGPU c = counters_.read();
    return {c.translucent_pixels, c.covered_pixels};
  }
  std::uint64_t bssrdf_samples_last_frame() const override {
    return static_cast<std::uint64_t>(counters_.read().translucent_pixels) * 3u * static_cast<std::uint64_t>(params_.integer("N")) *
           static_cast<std::uint64_t>(light_gbuffer_.light_count());
  }
  std::size_t gpu_memory_bytes() const override {
    return light_gbuffer_.gpu_memory_bytes() + static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 16;
  }

 private:
  void resize(int width, int height) {
    glDeleteTextures(1, &accumulated_);
    glCreateTextures(GL_TEXTURE_2D, 1, &accumulated_);
    glTextureStorage2D(accumulated_, 1, GL_RGBA32F, width, height);
    gpu::label_object(GL_TEXTURE, accumulated_, "per-pixel accumulated radiosity");
    width_ = width, height_ = height;
  }

  const ParamValues& params_;
  render::LightGBuffer light_gbuffer_;
  gpu::ShaderProgram program_;
  GLuint accumulated_ = 0;
  gpu::FrameCounters counters_;
  int width_ = 0, height_ = 0, accumulated_frames_ = 0;
  glm::mat4 last_camera_{0.0f};
};

}  // namespace

std::span<const ParamDecl> per_pixel_params() { return kParams; }

std::unique_ptr<Method> create_per_pixel(const Scene& scene, const render::SceneGpu& scene_gpu) {
  return std::make_unique<PerPixel>(scene, scene_gpu);
}

}  // namespace lucent::methods
