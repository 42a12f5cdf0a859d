// hybrid.cpp: the hybrid of Chang, Lin, Lee, Chen, "Real-Time Translucent Rendering Using GPU-based Texture Space
// Importance Sampling", CGF 27(2), 2008, Section 4: R_d = R_d W_l + R_d W_g (bssrdf/hybrid_split.h). The global
// term is texture-space importance sampling as in texture-space-is (texture_space/irradiance_sampler.h: E' into
// the atlas, N texels by the inverse CDF) with the model's full S_d times W_g in Eq. 11; the local term a circular
// pattern of L C + 1 points around each shaded point in each light's sampling plane, looked up in the light G-buffer
// (shade.comp), whose radii and weights are tabulated per material on the CPU.
#include "methods/method.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "bssrdf/hybrid_split.h"
#include "gpu/gl_debug.h"
#include "gpu/shader_program.h"
#include "lucent/error.h"
#include "methods/hybrid/hybrid_io.h"
#include "platform/gl_capabilities.h"
#include "render/light_gbuffer.h"
#include "render/view_accumulator.h"
#include "texture_space/irradiance_sampler.h"
#include "texture_space/texture_gbuffer.h"

namespace lucent::methods {
namespace {

constexpr texture_space::SamplerSlots kSamplerSlots{LUCENT_IMAGE_HYBRID_SOURCE, LUCENT_IMAGE_HYBRID_TARGET,
                                                    LUCENT_TEX_HYBRID_PYRAMID, LUCENT_BINDING_HYBRID_SAMPLES,
                                                    LUCENT_BINDING_HYBRID_ROW_CDF};

std::string irradiance_defines(const Scene& scene) {
  return render::light_sampling_defines(scene) +
         fmt::format("#define TSIS_TEX_POSITION {}\n#define TSIS_TEX_NORMAL_RATIO {}\n", texture_space::kTexturePosition,
                     texture_space::kTextureNormalRatio);
}

std::string shade_defines(const Scene& scene) {
  return render::light_sampling_defines(scene) + fmt::format("#define HYBRID_TEX_POSITION {}\n#define HYBRID_TEX_NORMAL_RATIO {}\n", texture_space::kTexturePosition,
                     texture_space::kTextureNormalRatio);
}

int order_of(const ParamValues& params) { return texture_space::sampling_order(params.text("order")); }

// Loop iterations of one shade.comp invocation, all loops counted (the band loops of 3 and, with several lights,
// each global sample's loop over the lights with its shadow lookup of taps^2 + taps): the global sum, then per
// light the L + 1 strata (with their band loop) and the L C + 1 points (with theirs).
// `sd`: the loop iterations of one S_d evaluation (photon beam diffusion's integral; 0 for the closed forms).
std::uint64_t shade_loop_iterations(std::uint64_t N, std::uint64_t lights, std::uint64_t L, std::uint64_t C,
                                    std::uint64_t taps, std::uint64_t sd) {
  const std::uint64_t per_global = 1 + (lights > 1 ? lights * (1 + 3 + taps * taps + taps + 3 * sd) + 3 : 1 + 3 * sd);
  return N * per_global + lights * ((L + 1) * (4 + 3 * sd) + (L * C + 1) * (4 + 3 * sd));
}

// R_p [scene units] of a material: the largest over the bands (Section 4.1).
float split_radius(const Material& material, float scale_mm, float c) {
  float Rp = 0.0f;
  const glm::vec3 sigma_a = material.sigma_a * scale_mm, sigma_s = material.sigma_s * scale_mm;
  for (int band = 0; band < 3; ++band) {
    shader::BandMedium m = shader::make_band_medium(sigma_a[band], sigma_s[band], material.g[band]);
    m.thickness = material.thickness_mm / scale_mm;
    const float r_max = 16.0f / std::max(m.sigma_tr, 1e-4f * m.sigma_t_prime);
    Rp = std::max(Rp, shader::hybrid_band_Rp(static_cast<int>(material.model), m, material.eta, c, r_max));
  }
  return Rp;
}

}  // namespace

class Hybrid final : public Method {
 public:
  Hybrid(const Scene& scene, const render::SceneGpu& scene_gpu, const texture_space::SceneAtlas& atlas)
      : params_(scene.method_params),
        light_gbuffer_(scene, scene_gpu, params_.integer("light_map_size")),
        iterations_per_sample_(render::light_sampling_iterations_per_sample(scene)),
        texture_gbuffer_(scene_gpu, atlas),
        sampler_(texture_gbuffer_.size(), kSamplerSlots, irradiance_defines(scene)),
        shade_(gpu::ShaderProgram::compute("methods/hybrid/shaders/shade.comp", shade_defines(scene))) {
    glCreateBuffers(1, &block_buffer_);
    glNamedBufferStorage(block_buffer_, sizeof(shader::HybridGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, block_buffer_, "hybrid block");
    upload_pattern(scene);
  }
  ~Hybrid() override {
    glDeleteBuffers(1, &block_buffer_);
    glDeleteBuffers(1, &pattern_buffer_);
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
    const shader::HybridGPU block{glm::ivec4(params_.integer("N"), rings_, ring_points_, rings_ + 2),
                                  glm::vec4(K_, 0.0f, 0.0f, 0.0f)};
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
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_HYBRID_PATTERN, pattern_buffer_);
    accumulated_.bind(LUCENT_IMAGE_HYBRID_SUM);
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
    out.push_back({"local_samples", static_cast<double>(rings_ * ring_points_ + 1), ""});
    out.push_back({"split_radius", static_cast<double>(split_radius_mm_), "mm"});
    out.push_back({"texels_lit", static_cast<double>(record.counters.method_counts[0]), ""});
    out.push_back({"irradiance_total", static_cast<double>(total), "W"});
  }
  // N, order, specular and roughness are read every frame; the rest rebuilds.
  bool update_live_params(const Scene& scene) override {
    (void)scene;
    return true;
  }
  // The local pattern depends on the materials: tabulated again.
  bool update_materials(const Scene& scene) override {
    upload_pattern(scene);
    iterations_per_sample_ = render::light_sampling_iterations_per_sample(scene);
    return true;
  }
  std::size_t gpu_memory_bytes() const override {
    const std::size_t atlas = static_cast<std::size_t>(texture_gbuffer_.size()) * static_cast<std::size_t>(texture_gbuffer_.size());
    return light_gbuffer_.gpu_memory_bytes() + atlas * 36 + sampler_.gpu_memory_bytes() + pattern_bytes_ +
           accumulated_.gpu_memory_bytes();
  }

 private:
  static constexpr int kShadowTaps = 3;

  // Mesa llvmpipe ends a shader's loops past a budget (platform::check_loop_iterations): a setting that would pass
  // it is one clear error, not a silently dark image. The shader clamps N, L and C to hybrid_io.h's bounds besides.
  void check_loop_budget(int lights) const {
    const std::uint64_t N = static_cast<std::uint64_t>(params_.integer("N"));
    const std::uint64_t n = shade_loop_iterations(N, static_cast<std::uint64_t>(lights), rings_, ring_points_,
                                                  kShadowTaps, iterations_per_sample_ - 1u);
    if (n > platform::kLlvmpipeLoopBudget)  // formats the message only then
      platform::check_loop_iterations(fmt::format("hybrid: N {}, rings x ring_points {} x {}, {} light(s){}", N, rings_,
                                                  ring_points_, lights, iterations_per_sample_ > 1 ? ", photon beam" : ""),
                                      n, "lower method.N, rings or ring_points");
  }

  // Per translucent object (the order of SceneGpu's materials): R_p, then the L + 1 strata of hybrid_ring.
  void upload_pattern(const Scene& scene) {
    rings_ = params_.integer("rings");
    ring_points_ = params_.integer("ring_points");
    K_ = static_cast<float>(params_.number("K")) * scene.scale_mm;
    const float c = static_cast<float>(params_.number("importance_threshold")) * scene.scale_mm;
    std::vector<glm::vec4> table;
    split_radius_mm_ = -1.0f;
    for (const auto& object : scene.objects) {
      if (!object.translucent()) continue;
      const Material& material = *object.material;
      const float Rp = split_radius(material, scene.scale_mm, c);
      if (split_radius_mm_ < 0.0f) split_radius_mm_ = Rp * scene.scale_mm;
      table.push_back(glm::vec4(Rp, 0.0f, 0.0f, 0.0f));
      const glm::vec3 sigma_a = material.sigma_a * scene.scale_mm, sigma_s = material.sigma_s * scene.scale_mm;
      shader::BandMedium m[3];
      for (int band = 0; band < 3; ++band) {
        m[band] = shader::make_band_medium(sigma_a[band], sigma_s[band], material.g[band]);
        m[band].thickness = material.thickness_mm / scene.scale_mm;
      }
      for (int ring = 0; ring <= rings_; ++ring)
        table.push_back(shader::hybrid_ring(static_cast<int>(material.model), m[0], m[1], m[2], material.eta, Rp, K_, ring,
                                            rings_, ring_points_));
    }
    if (table.empty()) table.push_back(glm::vec4(0.0f));
    split_radius_mm_ = std::max(split_radius_mm_, 0.0f);
    const auto bytes = static_cast<GLsizeiptr>(table.size() * sizeof(glm::vec4));
    if (pattern_buffer_ == 0 || static_cast<std::size_t>(bytes) != pattern_bytes_) {
      glDeleteBuffers(1, &pattern_buffer_);
      glCreateBuffers(1, &pattern_buffer_);
      glNamedBufferStorage(pattern_buffer_, bytes, table.data(), GL_DYNAMIC_STORAGE_BIT);
      gpu::label_object(GL_BUFFER, pattern_buffer_, "hybrid local pattern");
      pattern_bytes_ = static_cast<std::size_t>(bytes);
    } else {
      glNamedBufferSubData(pattern_buffer_, 0, bytes, table.data());
    }
  }

  const ParamValues& params_;
  render::LightGBuffer light_gbuffer_;
  std::uint64_t iterations_per_sample_ = 1;  // loop iterations of one S_d evaluation plus one
  texture_space::TextureGBuffer texture_gbuffer_;
  texture_space::IrradianceSampler sampler_;
  gpu::ShaderProgram shade_;
  render::ViewAccumulator accumulated_{"hybrid accumulated radiosity"};
  GLuint block_buffer_ = 0, pattern_buffer_ = 0;
  std::size_t pattern_bytes_ = 0;
  int rings_ = 1, ring_points_ = 1;
  float K_ = 1.0f, split_radius_mm_ = 0.0f;
  std::uint32_t seed_ = 0, frame_index_ = 0;
};

std::unique_ptr<Method> create_hybrid(const MethodSetup& setup) {
  if (!setup.atlas) throw Error("hybrid: the renderer gave no texture atlas");
  return std::make_unique<Hybrid>(setup.scene, setup.scene_gpu, *setup.atlas);
}

}  // namespace lucent::methods
