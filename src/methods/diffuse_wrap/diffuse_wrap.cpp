// diffuse_wrap.cpp: the lower-bound baseline of what game engines ship for translucent materials: no light travels
// under the surface; each pixel is a Lambertian surface with wrap lighting whose albedo is the material's total
// diffuse reflectance (bssrdf/diffuse_albedo.h), with the boundary's Fresnel transmittance on the way in and out.
// Shadows from the shared light G-buffer. Shader: src/methods/diffuse_wrap/shaders/shade.comp; docs/methods/diffuse-wrap.md.
#include "methods/method.h"

#include "gpu/gl_debug.h"
#include "gpu/shader_program.h"
#include "methods/diffuse_wrap/diffuse_wrap_io.h"
#include "render/light_gbuffer.h"

namespace lucent::methods {
namespace {

class DiffuseWrap final : public Method {
 public:
  DiffuseWrap(const Scene& scene, const render::SceneGpu& scene_gpu)
      : params_(scene.method_params),
        light_gbuffer_(scene, scene_gpu, params_.integer("light_map_size")),
        program_(gpu::ShaderProgram::compute("methods/diffuse_wrap/shaders/shade.comp", render::light_sampling_defines(scene))) {
    glCreateBuffers(1, &block_buffer_);
    glNamedBufferStorage(block_buffer_, sizeof(shader::DiffuseWrapGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, block_buffer_, "diffuse-wrap block");
  }
  ~DiffuseWrap() override { glDeleteBuffers(1, &block_buffer_); }

  void prepare_frame(shader::FrameGPU& frame, bool restart) override {
    (void)restart;
    width_ = frame.output_size.x, height_ = frame.output_size.y;
    light_gbuffer_.fill_frame(frame);
    frame.light_counts.w = params_.integer("visibility_taps");
    frame.shading = glm::vec4(params_.boolean("specular") ? 1.0f : 0.0f, params_.number("roughness"), 0.0f, 0.0f);
    const shader::DiffuseWrapGPU block{glm::vec4(params_.number("wrap"), 0.0f, 0.0f, 0.0f)};
    glNamedBufferSubData(block_buffer_, 0, sizeof(block), &block);
  }

  void render(const FrameContext& context) override {
    light_gbuffer_.render(context.scene_gpu, context.profiler);
    auto pass = context.profiler.pass("shade");
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_METHOD, block_buffer_);
    light_gbuffer_.bind_textures();
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUseProgram(program_.id());
    glDispatchCompute(static_cast<GLuint>((width_ + 7) / 8), static_cast<GLuint>((height_ + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }

  int accumulated_frames() const override { return 1; }
  void statistics(const FrameRecord& record, std::vector<FrameStatistic>& out) const override {
    (void)record;
    (void)out;
  }
  bool update_live_params(const Scene& scene) override {
    (void)scene;
    return true;
  }
  bool update_materials(const Scene& scene) override {
    (void)scene;
    return true;
  }
  std::size_t gpu_memory_bytes() const override { return light_gbuffer_.gpu_memory_bytes(); }

 private:
  const ParamValues& params_;
  render::LightGBuffer light_gbuffer_;
  gpu::ShaderProgram program_;
  GLuint block_buffer_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace

std::unique_ptr<Method> create_diffuse_wrap(const MethodSetup& setup) {
  return std::make_unique<DiffuseWrap>(setup.scene, setup.scene_gpu);
}

}  // namespace lucent::methods
