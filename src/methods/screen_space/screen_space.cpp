// screen_space.cpp: separable screen-space subsurface scattering as game engines ship it (Jimenez et al. 2015):
// the transmitted irradiance per camera pixel into an image, a horizontal and a vertical blur with a kernel from
// Burley's normalized-diffusion profile fitted to each material, or a sum of Gaussians fitted to it
// (screen_space_kernel.h), its width the profile's world-space radius projected to pixels at each pixel's depth,
// depth-aware; then L = F_t(w_o) albedo E / pi. Light crossing thin parts from behind (thickness from the light
// G-buffer, the profile's transmittance) is added to the blurred irradiance in the last pass.
// Shaders: src/methods/screen_space/shaders/; docs/methods/screen-space.md.
#include "methods/method.h"

#include "gpu/gl_debug.h"
#include "gpu/shader_program.h"
#include "methods/screen_space/screen_space_io.h"
#include "methods/screen_space/screen_space_kernel.h"
#include "render/light_gbuffer.h"
#include "render/view_accumulator.h"

namespace lucent::methods {
namespace {

class ScreenSpace final : public Method {
 public:
  ScreenSpace(const Scene& scene, const render::SceneGpu& scene_gpu)
      : params_(scene.method_params),
        light_gbuffer_(scene, scene_gpu, params_.integer("light_map_size")),
        irradiance_program_(gpu::ShaderProgram::compute("methods/screen_space/shaders/irradiance.comp",
                                                        render::light_sampling_defines(scene))),
        horizontal_program_(gpu::ShaderProgram::compute("methods/screen_space/shaders/blur.comp")),
        vertical_program_(gpu::ShaderProgram::compute("methods/screen_space/shaders/blur.comp",
                                                      "#define LUCENT_BLUR_VERTICAL 1\n")),
        shade_program_(gpu::ShaderProgram::compute("methods/screen_space/shaders/shade.comp",
                                                   render::light_sampling_defines(scene))) {
    glCreateBuffers(1, &block_buffer_);
    glNamedBufferStorage(block_buffer_, sizeof(shader::ScreenSpaceGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, block_buffer_, "screen-space block");
    upload_kernels(scene);
  }
  ~ScreenSpace() override {
    glDeleteBuffers(1, &block_buffer_);
    glDeleteBuffers(1, &kernel_buffer_);
  }

  void prepare_frame(shader::FrameGPU& frame, bool restart) override {
    irradiance_.begin_frame(frame, restart);
    horizontal_.begin_frame(frame, restart);
    blurred_.begin_frame(frame, restart);
    light_gbuffer_.fill_frame(frame);
    frame.light_counts.w = params_.integer("visibility_taps");
    frame.shading = glm::vec4(params_.boolean("specular") ? 1.0f : 0.0f, params_.number("roughness"), 0.0f, 0.0f);
    const shader::ScreenSpaceGPU block{glm::ivec4(taps_, profile_, params_.boolean("transmittance") ? 1 : 0, 0),
                                       glm::vec4(params_.number("depth_threshold"), 0.0f, 0.0f, 0.0f)};
    glNamedBufferSubData(block_buffer_, 0, sizeof(block), &block);
  }

  void render(const FrameContext& context) override {
    light_gbuffer_.render(context.scene_gpu, context.profiler);
    const GLuint groups_x = static_cast<GLuint>((irradiance_.width() + 7) / 8);
    const GLuint groups_y = static_cast<GLuint>((irradiance_.height() + 7) / 8);
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_METHOD, block_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_SCREEN_SPACE_KERNEL, kernel_buffer_);
    light_gbuffer_.bind_textures();
    irradiance_.bind(LUCENT_IMAGE_SCREEN_SPACE_IRRADIANCE);
    horizontal_.bind(LUCENT_IMAGE_SCREEN_SPACE_HORIZONTAL);
    blurred_.bind(LUCENT_IMAGE_SCREEN_SPACE_BLURRED);
    const std::pair<const char*, const gpu::ShaderProgram*> passes[] = {
        {"irradiance", &irradiance_program_}, {"blur_horizontal", &horizontal_program_}, {"blur_vertical", &vertical_program_}};
    for (const auto& [name, program] : passes) {
      auto pass = context.profiler.pass(name);
      glUseProgram(program->id());
      glDispatchCompute(groups_x, groups_y, 1);
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    auto pass = context.profiler.pass("shade");
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUseProgram(shade_program_.id());
    glDispatchCompute(groups_x, groups_y, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }

  int accumulated_frames() const override { return 1; }
  void statistics(const FrameRecord& record, std::vector<FrameStatistic>& out) const override {
    const double ms = record.pass_ms("blur_horizontal") + record.pass_ms("blur_vertical");
    out.push_back({"blur_taps", static_cast<double>(record.counters.translucent_pixels) * 2.0 * taps_, ""});
    out.push_back({"blur_ms", ms, "ms"});
  }
  bool update_live_params(const Scene& scene) override {
    upload_kernels(scene);
    return true;
  }
  bool update_materials(const Scene& scene) override {
    upload_kernels(scene);
    return true;
  }
  std::size_t gpu_memory_bytes() const override {
    return light_gbuffer_.gpu_memory_bytes() + irradiance_.gpu_memory_bytes() + horizontal_.gpu_memory_bytes() +
           blurred_.gpu_memory_bytes() + kernel_bytes_;
  }

 private:
  // The kernels depend on the materials, the tap count and the profile only (offsets in scene units, not pixels).
  void upload_kernels(const Scene& scene) {
    taps_ = scene.method_params.integer("taps");
    profile_ = scene.method_params.text("profile") == "gaussians" ? LUCENT_SCREEN_SPACE_PROFILE_GAUSSIANS
                                                                   : LUCENT_SCREEN_SPACE_PROFILE_BURLEY;
    const std::vector<shader::ScreenSpaceTapGPU> kernels = screen_space::scene_kernels(scene, taps_, profile_);
    const std::size_t bytes = kernels.size() * sizeof(shader::ScreenSpaceTapGPU);
    if (bytes != kernel_bytes_) {
      glDeleteBuffers(1, &kernel_buffer_);
      glCreateBuffers(1, &kernel_buffer_);
      glNamedBufferStorage(kernel_buffer_, static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
      gpu::label_object(GL_BUFFER, kernel_buffer_, "screen-space kernels");
      kernel_bytes_ = bytes;
    }
    glNamedBufferSubData(kernel_buffer_, 0, static_cast<GLsizeiptr>(bytes), kernels.data());
  }

  const ParamValues& params_;
  render::LightGBuffer light_gbuffer_;
  gpu::ShaderProgram irradiance_program_, horizontal_program_, vertical_program_, shade_program_;
  render::ViewAccumulator irradiance_{"screen-space irradiance"}, horizontal_{"screen-space horizontal blur"},
      blurred_{"screen-space blurred irradiance"};
  GLuint block_buffer_ = 0, kernel_buffer_ = 0;
  std::size_t kernel_bytes_ = 0;
  int taps_ = 0, profile_ = LUCENT_SCREEN_SPACE_PROFILE_BURLEY;
};

}  // namespace

std::unique_ptr<Method> create_screen_space(const MethodSetup& setup) {
  return std::make_unique<ScreenSpace>(setup.scene, setup.scene_gpu);
}

}  // namespace lucent::methods
