// per_pixel.cpp: the caching-free baseline of Dal Corso et al. 2015, Fig. 11 ("no cache"): the light-space
// sampling of eq. 9 evaluated per screen pixel every frame, as translucent shadow maps do, instead of per map
// texel. Same light G-buffer (step 1) and estimator as radiosity-maps; cost grows with the pixels the
// translucent objects cover, which is what the break-even measurement of Fig. 11 varies.
// Shader: src/methods/per_pixel/shaders/shade.comp.
#include "methods/method.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "methods/per_pixel/per_pixel_io.h"
#include "gpu/shader_program.h"
#include "platform/gl_capabilities.h"
#include "render/light_gbuffer.h"
#include "render/view_accumulator.h"

namespace lucent::methods {
namespace {

class PerPixel final : public Method {
 public:
  PerPixel(const Scene& scene, const render::SceneGpu& scene_gpu)
      : params_(scene.method_params),
        light_gbuffer_(scene, scene_gpu, params_.integer("light_map_size")),
        iterations_per_sample_(render::light_sampling_iterations_per_sample(scene)),
        program_(gpu::ShaderProgram::compute("methods/per_pixel/shaders/shade.comp", render::light_sampling_defines(scene))) {
    glCreateBuffers(1, &block_buffer_);
    glNamedBufferStorage(block_buffer_, sizeof(shader::PerPixelGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, block_buffer_, "per-pixel block");
  }
  ~PerPixel() override { glDeleteBuffers(1, &block_buffer_); }

  void prepare_frame(shader::FrameGPU& frame, bool restart) override {
    // View dependent: a camera change restarts accumulation too.
    restart = accumulated_.begin_frame(frame, restart || !params_.boolean("progressive"));
    light_gbuffer_.fill_frame(frame);
    render::check_light_sampling_loops("per-pixel", frame.light_counts.x, static_cast<std::uint64_t>(params_.integer("N")),
                                       iterations_per_sample_);
    frame.light_counts.w = params_.integer("visibility_taps");
    frame.seeds.z = restart ? 1u : 0u;
    frame.shading = glm::vec4(params_.boolean("specular") ? 1.0f : 0.0f, params_.number("roughness"), 0.0f, 0.0f);
    const shader::PerPixelGPU block{glm::ivec4(params_.integer("N"), 0, 0, 0)};
    glNamedBufferSubData(block_buffer_, 0, sizeof(block), &block);
  }

  void render(const FrameContext& context) override {
    light_gbuffer_.render(context.scene_gpu, context.profiler);
    auto pass = context.profiler.pass("per_pixel");
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_METHOD, block_buffer_);
    light_gbuffer_.bind_textures();
    accumulated_.bind(LUCENT_IMAGE_PER_PIXEL_SUM);
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUseProgram(program_.id());
    glDispatchCompute(static_cast<GLuint>((accumulated_.width() + 7) / 8), static_cast<GLuint>((accumulated_.height() + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }

  int accumulated_frames() const override { return accumulated_.frames(); }
  void statistics(const FrameRecord& record, std::vector<FrameStatistic>& out) const override {
    const double samples = static_cast<double>(record.counters.translucent_pixels) * 3.0 * params_.integer("N") *
                           light_gbuffer_.light_count();
    const double ms = record.pass_ms("per_pixel");
    out.push_back({"bssrdf_samples", samples, ""});
    out.push_back({"bssrdf_samples_per_second", ms > 0.0 ? samples / (ms * 1e-3) : 0.0, "1/s"});
  }
  // N, taps, specular and roughness are read every frame; materials from the scene's material buffer.
  bool update_live_params(const Scene& scene) override {
    (void)scene;
    return true;
  }
  bool update_materials(const Scene& scene) override {
    iterations_per_sample_ = render::light_sampling_iterations_per_sample(scene);
    return true;
  }
  std::size_t gpu_memory_bytes() const override {
    return light_gbuffer_.gpu_memory_bytes() + accumulated_.gpu_memory_bytes();
  }

 private:
  const ParamValues& params_;
  render::LightGBuffer light_gbuffer_;
  std::uint64_t iterations_per_sample_;  // shader loop iterations per BSSRDF sample (check_loop_iterations)
  gpu::ShaderProgram program_;
  render::ViewAccumulator accumulated_{"per-pixel accumulated radiosity"};
  GLuint block_buffer_ = 0;
};

}  // namespace

std::unique_ptr<Method> create_per_pixel(const MethodSetup& setup) {
  return std::make_unique<PerPixel>(setup.scene, setup.scene_gpu);
}

}  // namespace lucent::methods
