// texture_space_is.cpp: texture-space importance sampling (Chang, Lin, Lee, Chen, "Real-Time Translucent
// Rendering Using GPU-based Texture Space Importance Sampling", CGF 27(2), 2008, Section 3, without the hybrid
// with local sampling): stage 1 renders E' = (A_S / A_T) F_t E into the atlas (irradiance.comp), stage 2 draws N
// texels with density proportional to E' (both texture_space/irradiance_sampler.h), stage 3 sums the model's full S_d
// over those N samples for every camera pixel (shade.comp, Eq. 11 with each sample's position, normal and light). The texture-space G-buffer is redrawn every frame (deforming meshes).
#include "methods/method.h"

#include <cstring>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "gpu/shader_program.h"
#include "lucent/error.h"
#include "methods/texture_space_is/texture_space_is_io.h"
#include "platform/gl_capabilities.h"
#include "render/light_gbuffer.h"
#include "render/view_accumulator.h"
#include "texture_space/irradiance_sampler.h"
#include "texture_space/texture_gbuffer.h"

namespace lucent::methods {
namespace {

std::string defines(const Scene& scene) {
  return render::light_sampling_defines(scene) +
         fmt::format("#define TSIS_TEX_POSITION {}\n#define TSIS_TEX_NORMAL_RATIO {}\n", texture_space::kTexturePosition,
                     texture_space::kTextureNormalRatio);
}

constexpr texture_space::SamplerSlots kSamplerSlots{LUCENT_IMAGE_TSIS_SOURCE, LUCENT_IMAGE_TSIS_TARGET, LUCENT_TEX_TSIS_PYRAMID,
                                                 LUCENT_BINDING_TSIS_SAMPLES, LUCENT_BINDING_TSIS_ROW_CDF};

int order_of(const ParamValues& params) { return texture_space::sampling_order(params.text("order")); }

class TextureSpaceIs final : public Method {
 public:
  TextureSpaceIs(const Scene& scene, const render::SceneGpu& scene_gpu, const texture_space::SceneAtlas& atlas)
      : params_(scene.method_params),
        light_gbuffer_(scene, scene_gpu, params_.integer("light_map_size")),
        iterations_per_sample_(render::light_sampling_iterations_per_sample(scene)),
        texture_gbuffer_(scene_gpu, atlas),
        sampler_(texture_gbuffer_.size(), kSamplerSlots, defines(scene)),
        shade_(gpu::ShaderProgram::compute("methods/texture_space_is/shaders/shade.comp", defines(scene))) {
    glCreateBuffers(1, &block_buffer_);
    glNamedBufferStorage(block_buffer_, sizeof(shader::TextureSpaceIsGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, block_buffer_, "texture-space-is block");
  }
  ~TextureSpaceIs() override {
    glDeleteBuffers(1, &block_buffer_);
  }

  void prepare_frame(shader::FrameGPU& frame, bool restart) override {
    restart = accumulated_.begin_frame(frame, restart);  // view dependent: a camera move restarts too
    light_gbuffer_.fill_frame(frame);
    check_loop_budget(frame.light_counts.x);
    frame.light_counts.w = kShadowTaps;
    frame.seeds.z = restart ? 1u : 0u;
    seed_ = frame.seeds.x;
    frame_index_ = frame.seeds.y;
    frame.shading = glm::vec4(params_.boolean("specular") ? 1.0f : 0.0f, params_.number("roughness"), 0.0f, 0.0f);
    const shader::TextureSpaceIsGPU block{
        glm::ivec4(params_.integer("N"), order_of(params_), sampler_.pyramid_size(), sampler_.levels()),
        glm::ivec4(texture_gbuffer_.size(), 0, 0, 0)};
    glNamedBufferSubData(block_buffer_, 0, sizeof(block), &block);
  }

  void render(const FrameContext& context) override {
    sampler_.run_stages(light_gbuffer_, texture_gbuffer_, context.scene_gpu, context.profiler, params_.integer("N"),
                        order_of(params_), seed_, frame_index_);
    auto pass = context.profiler.pass("shade");
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_METHOD, block_buffer_);
    light_gbuffer_.bind_textures();
    texture_gbuffer_.bind_textures();
    sampler_.bind_samples();
    accumulated_.bind(LUCENT_IMAGE_TSIS_SUM);
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUseProgram(shade_.id());
    glDispatchCompute(static_cast<GLuint>((accumulated_.width() + 7) / 8), static_cast<GLuint>((accumulated_.height() + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }

  int accumulated_frames() const override { return accumulated_.frames(); }
  void statistics(const FrameRecord& record, std::vector<FrameStatistic>& out) const override {
    float total = 0.0f;
    std::memcpy(&total, &record.counters.method_counts[1], sizeof(total));
    out.push_back({"samples", static_cast<double>(params_.integer("N")), ""});
    out.push_back({"texels_lit", static_cast<double>(record.counters.method_counts[0]), ""});
    out.push_back({"irradiance_total", static_cast<double>(total), "W"});
  }
  // N, order, specular and roughness are read every frame; materials from the scene's material buffer.
  bool update_live_params(const Scene& scene) override {
    (void)scene;
    return true;
  }
  bool update_materials(const Scene& scene) override {
    iterations_per_sample_ = render::light_sampling_iterations_per_sample(scene);
    return true;
  }
  std::size_t gpu_memory_bytes() const override {
    const std::size_t atlas = static_cast<std::size_t>(texture_gbuffer_.size()) * static_cast<std::size_t>(texture_gbuffer_.size());
    return light_gbuffer_.gpu_memory_bytes() + atlas * 36 + sampler_.gpu_memory_bytes() +
           accumulated_.gpu_memory_bytes();
  }

 private:
  static constexpr int kShadowTaps = 3;

  // Mesa llvmpipe ends a shader's loops past a budget (platform::check_loop_iterations). shade.comp loops over the
  // N samples and, with several lights, over the lights per sample (transmitted_sd.glsl: bands and a shadow lookup
  // of taps^2 + taps each); each S_d of photon beam diffusion is a loop of its own (iterations_per_sample_ - 1):
  // a setting that would pass the budget is one clear error, not a silently dark image.
  void check_loop_budget(int lights) const {
    const std::uint64_t N = static_cast<std::uint64_t>(params_.integer("N")), l = static_cast<std::uint64_t>(lights);
    const std::uint64_t sd = 3u * (iterations_per_sample_ - 1u);  // the three bands' S_d loops
    const std::uint64_t per_sample =
        1u + (l > 1u ? l * (1u + 3u + kShadowTaps * kShadowTaps + kShadowTaps + sd) + 3u : 1u + sd);
    if (N * per_sample > platform::kLlvmpipeLoopBudget)  // formats the message only then
      platform::check_loop_iterations(
          fmt::format("texture-space-is: N {} x {} per sample ({} light(s){})", N, per_sample, lights,
                      sd > 0u ? ", photon beam" : ""),
          N * per_sample, fmt::format("lower method.N to {}", platform::kLlvmpipeLoopBudget / per_sample));
  }

  const ParamValues& params_;
  render::LightGBuffer light_gbuffer_;
  std::uint64_t iterations_per_sample_ = 1;  // loop iterations of one S_d evaluation plus one
  texture_space::TextureGBuffer texture_gbuffer_;
  texture_space::IrradianceSampler sampler_;
  gpu::ShaderProgram shade_;
  render::ViewAccumulator accumulated_{"texture-space-is accumulated radiance"};
  GLuint block_buffer_ = 0;
  std::uint32_t seed_ = 0, frame_index_ = 0;
};

}  // namespace

std::unique_ptr<Method> create_texture_space_is(const MethodSetup& setup) {
  if (!setup.atlas) throw Error("texture-space-is: the renderer gave no texture atlas");
  return std::make_unique<TextureSpaceIs>(setup.scene, setup.scene_gpu, *setup.atlas);
}

}  // namespace lucent::methods
