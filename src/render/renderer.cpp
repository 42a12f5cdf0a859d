// renderer.cpp: one frame = camera G-buffer, the method's passes, tone mapping, blit to the target.
#include "lucent/renderer.h"

#include <fmt/format.h>

#include "gpu/gbuffer.h"
#include "gpu/gl_debug.h"
#include "gpu/gpu_timer.h"
#include "gpu/shader_program.h"
#include "lucent/error.h"
#include "methods/method.h"
#include "platform/gl_capabilities.h"
#include "render/environment_texture.h"
#include "render/scene_gpu.h"
#include "shared/shader_io.h"

namespace lucent {
namespace {

GLuint make_image_texture(int width, int height, GLenum format, const char* label) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, format, width, height);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gpu::label_object(GL_TEXTURE, texture, label);
  return texture;
}

// Output-sized images: HDR radiance, the tone-mapped image and a framebuffer to blit it from.
struct OutputImages {
  int width = 0, height = 0;
  GLuint hdr = 0, ldr = 0, ldr_framebuffer = 0;
  std::unique_ptr<gpu::GBuffer> camera_gbuffer;

  void resize(int w, int h) {
    if (w == width && h == height) return;
    release();
    width = w, height = h;
    hdr = make_image_texture(w, h, GL_RGBA32F, "radiance (HDR)");
    ldr = make_image_texture(w, h, GL_RGBA8, "display (tone-mapped)");
    glCreateFramebuffers(1, &ldr_framebuffer);
    glNamedFramebufferTexture(ldr_framebuffer, GL_COLOR_ATTACHMENT0, ldr, 0);
    camera_gbuffer = std::make_unique<gpu::GBuffer>(w, h, 0, "camera G-buffer");
  }
  void release() {
    if (!hdr) return;
    GLuint textures[] = {hdr, ldr};
    glDeleteTextures(2, textures);
    glDeleteFramebuffers(1, &ldr_framebuffer);
    camera_gbuffer.reset();
    hdr = ldr = ldr_framebuffer = 0;
  }
  ~OutputImages() { release(); }
};

glm::mat4 clip_from_world(const Camera& camera, float aspect, float scene_radius, glm::vec3 scene_center) {
  float distance = glm::length(camera.eye - scene_center);
  float z_far = distance + 2.0f * scene_radius;
  float z_near = std::max(z_far * 1e-4f, distance - 2.0f * scene_radius);
  return camera.clip_from_view(aspect, z_near, z_far) * camera.view_from_world();
}

}  // namespace

struct Renderer::Impl {
  Scene scene;
  std::unique_ptr<render::SceneGpu> scene_gpu;
  std::unique_ptr<methods::Method> method;
  std::unique_ptr<render::EnvironmentTexture> environment;
  gpu::ShaderProgram camera_program, tonemap_program;
  gpu::GpuTimer timer;
  GLuint frame_buffer = 0;
  OutputImages output;
  bool restart = true;
  double time_seconds = 0.0;
  bool geometry_dirty = true;  // animated geometry must be brought to time_seconds before the next frame
  unsigned frame_counter = 0;
  FrameTimings timings;

  explicit Impl(Scene s) : scene(std::move(s)) {
    if (platform::current_capabilities().version.empty())
      throw Error("no OpenGL context: create one (lucent::create_headless_context) before lucent::Renderer");
    camera_program = gpu::ShaderProgram::graphics("gbuffer/gbuffer.vert", "", "gbuffer/gbuffer.frag",
                                                  "#define CAMERA_VIEW 1\n");
    tonemap_program = gpu::ShaderProgram::compute("common/tonemap.comp");
    glCreateBuffers(1, &frame_buffer);
    glNamedBufferStorage(frame_buffer, sizeof(shader::FrameGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, frame_buffer, "frame");
    rebuild();
  }
  ~Impl() { glDeleteBuffers(1, &frame_buffer); }

  void rebuild() {
    const methods::MethodInfo* info = methods::find_method(scene.method);
    if (!info) throw Error(fmt::format("{}: unknown method '{}'", scene.source, scene.method));
    method.reset();
    scene_gpu = std::make_unique<render::SceneGpu>(scene);
    geometry_dirty = true;
    environment.reset();
    if (scene.environment && scene.environment->map)
      environment = std::make_unique<render::EnvironmentTexture>(*scene.environment->map);
    method = info->create(scene, *scene_gpu);
    restart = true;
  }

  shader::FrameGPU frame_block(const Camera& camera) {
    shader::FrameGPU frame{};
    render::BoundingSphere bounds = scene_gpu->scene_bounds();
    float aspect = static_cast<float>(output.width) / static_cast<float>(output.height);
    frame.clip_from_world = clip_from_world(camera, aspect, bounds.radius, bounds.center);
    frame.camera_position = glm::vec4(camera.eye, 1.0f);
    frame.background = glm::vec4(scene.render.background, 0.0f);
    frame.sizes.z = output.width;
    frame.sizes.w = output.height;
    frame.seeds.x = scene.render.seed;
    frame.seeds.y = ++frame_counter;
    frame.options.x = std::exp2(scene.render.exposure);
    frame.options.w = static_cast<float>(static_cast<int>(scene.render.tonemap));
    if (environment)
      frame.extra_counts.w = LUCENT_ENVIRONMENT_MAP | (scene.environment->background ? LUCENT_ENVIRONMENT_BACKGROUND : 0);
    method->prepare_frame(frame, restart);
    return frame;
  }

  void camera_gbuffer_pass() {
    gpu::DebugGroup group("camera_gbuffer");
    timer.begin("camera_gbuffer");
    output.camera_gbuffer->begin_pass();
    glUseProgram(camera_program.id());
    scene_gpu->draw_all();
    timer.end();
    output.camera_gbuffer->bind_textures(LUCENT_TEX_CAMERA_POSITION, LUCENT_TEX_CAMERA_NORMAL, 15);
  }

  void tonemap_pass() {
    gpu::DebugGroup group("tonemap");
    timer.begin("tonemap");
    glBindTextureUnit(LUCENT_TEX_HDR, output.hdr);
    glBindImageTexture(LUCENT_IMAGE_LDR, output.ldr, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    glUseProgram(tonemap_program.id());
    glDispatchCompute(static_cast<GLuint>((output.width + 7) / 8), static_cast<GLuint>((output.height + 7) / 8), 1);
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    timer.end();
  }

  void summarize() {
    timings = FrameTimings{};
    for (auto& [name, ms] : timer.resolve()) {
      timings.passes.push_back({name, ms});
      if (name.rfind("isosurface", 0) == 0) timings.geometry_ms += ms;
      else if (name == "light_gbuffer") timings.light_gbuffer_ms += ms;
      else if (name == "map_gbuffers" || name == "integrate" || name == "mipmaps") timings.radiosity_maps_ms += ms;
      else timings.combine_ms += ms;
      timings.total_ms += ms;
    }
    timings.bssrdf_samples = method->bssrdf_samples_last_frame();
    glm::uvec2 coverage = method->pixel_coverage();
    timings.translucent_pixels = coverage.x;
    timings.map_coverage = coverage.x > 0 ? static_cast<double>(coverage.y) / coverage.x : 1.0;
    // Output images: RGBA32F radiance, RGBA8 display, camera G-buffer (RGBA32F + RGBA16F + DEPTH32F).
    std::size_t pixels = static_cast<std::size_t>(output.width) * static_cast<std::size_t>(output.height);
    timings.gpu_memory_bytes = method->gpu_memory_bytes() + pixels * (16 + 4 + 16 + 8 + 4);
  }

  void render(const Camera& camera, const RenderTarget& target) {
    if (target.width <= 0 || target.height <= 0)
      throw Error(fmt::format("render target size {}x{} is empty", target.width, target.height));
    output.resize(target.width, target.height);
    timer.begin_frame();
    shader::FrameGPU frame = frame_block(camera);
    restart = false;
    glNamedBufferSubData(frame_buffer, 0, sizeof(frame), &frame);
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_FRAME, frame_buffer);
    if (geometry_dirty && scene_gpu->animated()) scene_gpu->update(time_seconds, &timer);
    geometry_dirty = false;
    scene_gpu->bind_buffers();
    if (environment) environment->bind();
    camera_gbuffer_pass();
    method->render({scene, *scene_gpu, *output.camera_gbuffer, output.hdr, timer, frame.seeds.z != 0});
    tonemap_pass();
    glBlitNamedFramebuffer(output.ldr_framebuffer, target.framebuffer, 0, 0, output.width, output.height, 0, 0,
                           target.width, target.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    summarize();
  }
};

Renderer::Renderer(Scene scene) : impl_(std::make_unique<Impl>(std::move(scene))) {}
Renderer::~Renderer() = default;

void Renderer::render(const Camera& camera, const RenderTarget& target) { impl_->render(camera, target); }
Scene& Renderer::scene() { return impl_->scene; }
const Scene& Renderer::scene() const { return impl_->scene; }
void Renderer::scene_changed() { impl_->rebuild(); }
void Renderer::set_time(double seconds) {
  if (seconds == impl_->time_seconds) return;
  impl_->time_seconds = seconds;
  if (impl_->scene_gpu->animated()) impl_->geometry_dirty = true, impl_->restart = true;
}
double Renderer::time() const { return impl_->time_seconds; }
void Renderer::restart() { impl_->restart = true; }
int Renderer::accumulated_frames() const { return impl_->method->accumulated_frames(); }
const FrameTimings& Renderer::timings() const { return impl_->timings; }
std::string Renderer::device_of_current_context() {
  const auto& caps = platform::current_capabilities();
  return caps.renderer + ", OpenGL " + caps.version;
}

std::string Renderer::device() const { return device_of_current_context(); }

std::vector<glm::vec4> Renderer::scattered_radiosity(const std::vector<glm::vec3>& points,
                                                     const std::vector<glm::vec3>& normals) const {
  if (points.size() != normals.size())
    throw Error(fmt::format("scattered_radiosity: {} points but {} normals", points.size(), normals.size()));
  std::vector<shader::ProbeGPU> probes(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    probes[i].position = glm::vec4(points[i], 0.0f);
    probes[i].normal = glm::vec4(normals[i], 0.0f);
  }
  probes = impl_->method->scattered_radiosity(std::move(probes));
  std::vector<glm::vec4> out;
  for (const shader::ProbeGPU& p : probes) out.push_back(p.radiosity);
  return out;
}

std::vector<VirtualPointLight> Renderer::virtual_point_lights() const {
  std::vector<VirtualPointLight> out;
  for (const shader::VplGPU& v : impl_->method->virtual_point_lights())
    out.push_back({glm::vec3(v.position), glm::vec3(v.normal), v.position.w, glm::vec3(v.radiosity), v.normal.w});
  return out;
}

namespace {

// Reads a texture into an image; GL rows start at the bottom, images at the top.
template <typename Image>
Image read_texture(GLuint texture, int width, int height, GLenum type, std::size_t bytes_per_channel) {
  Image image{width, height, {}};
  image.pixels.resize(static_cast<std::size_t>(width) * height * 4);
  glGetTextureImage(texture, 0, GL_RGBA, type, static_cast<GLsizei>(image.pixels.size() * bytes_per_channel),
                    image.pixels.data());
  std::size_t row = static_cast<std::size_t>(width) * 4;
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(image.pixels.begin() + static_cast<std::ptrdiff_t>(y * row),
                     image.pixels.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                     image.pixels.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row));
  return image;
}

}  // namespace

ImageRGBA32F Renderer::read_radiance() const {
  return read_texture<ImageRGBA32F>(impl_->output.hdr, impl_->output.width, impl_->output.height, GL_FLOAT, 4);
}

ImageRGBA8 Renderer::read_display() const {
  return read_texture<ImageRGBA8>(impl_->output.ldr, impl_->output.width, impl_->output.height, GL_UNSIGNED_BYTE, 1);
}

}  // namespace lucent
