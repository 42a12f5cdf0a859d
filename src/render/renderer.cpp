// renderer.cpp: one frame = camera G-buffer, the method's passes, tone mapping, blit to the target.
#include "lucent/renderer.h"

#include <fmt/format.h>

#include <map>
#include <optional>
#include <utility>

#include "denoise/denoiser.h"
#include "gpu/gbuffer.h"
#include "gpu/gl_debug.h"
#include "gpu/image_texture.h"
#include "gpu/frame_profiler.h"
#include "gpu/shader_program.h"
#include "lucent/error.h"
#include "methods/method.h"
#include "methods/precompute.h"
#include "platform/gl_capabilities.h"
#include "render/light_gbuffer.h"
#include "render/environment_texture.h"
#include "render/scene_gpu.h"
#include "shared/shader_io.h"
#include "texture_space/scene_atlas_cache.h"

namespace lucent {
namespace {

// Output-sized images: HDR radiance, the tone-mapped image and a framebuffer to blit it from.
struct OutputImages {
  int width = 0, height = 0;
  GLuint hdr = 0, ldr = 0, ldr_framebuffer = 0;
  std::unique_ptr<gpu::GBuffer> camera_gbuffer;

  bool with_uv = false;  // the camera G-buffer keeps texture coordinates (scenes with textured materials)

  void resize(int w, int h, bool uv) {
    if (w == width && h == height && uv == with_uv) return;
    release();
    width = w, height = h, with_uv = uv;
    hdr = gpu::make_image_texture(w, h, GL_RGBA32F, "radiance (HDR)");
    ldr = gpu::make_image_texture(w, h, GL_RGBA8, "display (tone-mapped)");
    glCreateFramebuffers(1, &ldr_framebuffer);
    glNamedFramebufferTexture(ldr_framebuffer, GL_COLOR_ATTACHMENT0, ldr, 0);
    camera_gbuffer = std::make_unique<gpu::GBuffer>(w, h, 0, "camera G-buffer", with_uv);
  }
  void release() {
    if (!hdr) return;
    GLuint textures[] = {hdr, ldr};
    glDeleteTextures(2, textures);
    glDeleteFramebuffers(1, &ldr_framebuffer);
    camera_gbuffer.reset();
    hdr = ldr = ldr_framebuffer = 0;
    width = height = 0;
  }
  ~OutputImages() { release(); }
};

glm::mat4 clip_from_world(const Camera& camera, float aspect, float scene_radius, glm::vec3 scene_center) {
  float distance = glm::length(camera.eye - scene_center);
  float z_far = distance + 2.0f * scene_radius;
  float z_near = std::max(z_far * 1e-4f, distance - 2.0f * scene_radius);
  return camera.clip_from_view(aspect, z_near, z_far) * camera.view_from_world();
}

// What a change to the scene touches: the method's live parameters, the materials, or more (a rebuild).
enum class SceneChange { None, Live, Materials, Rebuild };

bool same_mesh(const TriangleMesh& a, const TriangleMesh& b) {
  return a.positions == b.positions && a.normals == b.normals && a.indices == b.indices && a.uvs == b.uvs;
}

bool same_material(const Material& a, const Material& b) {
  const MediumField &f = a.field, &g = b.field;
  return a.sigma_a == b.sigma_a && a.sigma_s == b.sigma_s && a.g == b.g && a.eta == b.eta && a.model == b.model &&
         a.thickness_mm == b.thickness_mm &&
         f.type == g.type && f.scale_mm == g.scale_mm && f.contrast == g.contrast && f.file == g.file &&
         f.volume == g.volume && f.has_bounds == g.has_bounds && f.bounds_lower == g.bounds_lower &&
         f.bounds_upper == g.bounds_upper;
}

SceneChange classify_change(const Scene& built, const Scene& now) {
  if (built.method != now.method || built.objects.size() != now.objects.size() ||
      built.lights.size() != now.lights.size() || built.point_lights.size() != now.point_lights.size() ||
      built.environment.has_value() != now.environment.has_value())
    return SceneChange::Rebuild;
  for (std::size_t i = 0; i < built.lights.size(); ++i) {
    const DirectionalLight &a = built.lights[i], &b = now.lights[i];
    if (a.direction != b.direction || a.radiance != b.radiance || a.specular != b.specular) return SceneChange::Rebuild;
  }
  for (std::size_t i = 0; i < built.point_lights.size(); ++i) {
    const PointLight &a = built.point_lights[i], &b = now.point_lights[i];
    if (a.position != b.position || a.intensity != b.intensity || a.spot != b.spot || a.direction != b.direction ||
        a.inner_deg != b.inner_deg || a.outer_deg != b.outer_deg)
      return SceneChange::Rebuild;
  }
  if (built.environment &&
      (built.environment->file != now.environment->file || built.environment->light_count != now.environment->light_count ||
       built.environment->intensity != now.environment->intensity ||
       built.environment->background != now.environment->background || built.environment->map != now.environment->map))
    return SceneChange::Rebuild;
  // scale_mm converts point-light intensities and media fields as well as materials: a rebuild.
  if (built.scale_mm != now.scale_mm) return SceneChange::Rebuild;
  // The shaders compile the scene's models (one model alone, the table models' code): a model change that moves
  // their defines rebuilds.
  if (render::light_sampling_defines(built) != render::light_sampling_defines(now)) return SceneChange::Rebuild;
  bool materials = false;
  for (std::size_t i = 0; i < built.objects.size(); ++i) {
    const SceneObject &a = built.objects[i], &b = now.objects[i];
    if (a.translucent() != b.translucent() || a.blob_resolution != b.blob_resolution ||
        a.world_from_object != b.world_from_object || a.deformation.type != b.deformation.type ||
        a.deformation.amplitude != b.deformation.amplitude || a.deformation.period_s != b.deformation.period_s ||
        a.deformation.start_s != b.deformation.start_s ||
        !same_mesh(a.mesh, b.mesh))
      return SceneChange::Rebuild;
    // Other maps: the G-buffers' attachments, the shaders' defines and whether the method accepts them may change.
    if (a.material && a.material->maps != b.material->maps) return SceneChange::Rebuild;
    if (a.albedo != b.albedo) materials = true;
    if (a.material && !same_material(*a.material, *b.material)) materials = true;
  }
  // Method parameters: a change of any Rebuild parameter rebuilds; Live ones are taken per frame.
  bool live = false;
  const methods::MethodInfo* info = methods::find_method(now.method);
  for (const auto& [name, value] : now.method_params.all()) {
    if (built.method_params.has(name) && to_string(built.method_params.all().at(name)) == to_string(value)) continue;
    const ParamDecl* decl = nullptr;
    if (info)
      for (const ParamDecl& d : info->params)
        if (d.name == name) decl = &d;
    if (!decl || decl->update != ParamUpdate::Live) return SceneChange::Rebuild;
    live = true;
  }
  if (materials) return SceneChange::Materials;  // a method taking materials live also re-reads its parameters
  return live ? SceneChange::Live : SceneChange::None;
}

}  // namespace

struct Renderer::Impl {
  Scene scene;
  Scene built;  // the scene as the GPU resources were built from it (for scene_changed())
  RenderProgress progress;
  // needs_texture_atlas methods: the scene's atlas and the scene with its translucent meshes replaced by the atlas
  // meshes, as the GPU and the method see it (empty for other methods, which see `scene`).
  std::optional<texture_space::SceneAtlas> atlas;
  std::optional<Scene> atlas_scene;
  std::vector<std::byte> precomputed;  // the method's PrecomputeDecl bytes (empty when it has none)
  std::unique_ptr<render::SceneGpu> scene_gpu;
  std::unique_ptr<methods::Method> method;
  std::unique_ptr<render::EnvironmentTexture> environment;
  gpu::ShaderProgram camera_program, tonemap_program;
  gpu::FrameProfiler profiler;
  GLuint frame_buffer = 0;
  OutputImages output;
  bool restart = true;
  bool material_maps = false;  // the scene has textured materials: the camera G-buffer keeps texture coordinates
  double time_seconds = 0.0;
  bool geometry_dirty = true;  // animated geometry must be brought to time_seconds before the next frame
  std::uint64_t frame_counter = 0;
  // The denoising stage (made when the scene first enables it, released when it disables it), the camera and the
  // method's frame count of the previous frame (to tell a restart and its cause), and each frame's history length
  // until its statistics are reported.
  std::unique_ptr<denoise::Denoiser> denoiser;
  glm::mat4 previous_clip_from_world{0.0f};
  int previous_method_frames = 0;
  std::map<std::uint64_t, double> denoise_history;
  FrameTimings latest;                   // newest frame reported
  std::vector<FrameTimings> unclaimed;   // reported frames not yet taken by finished_frames()
  static constexpr std::size_t kMaxUnclaimed = 4096;

  Impl(Scene s, RenderProgress p) : scene(std::move(s)), progress(std::move(p)) {
    if (platform::current_capabilities().version.empty())
      throw Error("no OpenGL context: create one (lucent::create_headless_context) before lucent::Renderer");
    if (scene.method.empty()) scene.method = std::string(methods::default_method().name);
    camera_program = gpu::ShaderProgram::graphics("gbuffer/gbuffer.vert", "", "gbuffer/gbuffer.frag",
                                                  "#define CAMERA_VIEW 1\n");
    tonemap_program = gpu::ShaderProgram::compute("common/tonemap.comp");
    glCreateBuffers(1, &frame_buffer);
    glNamedBufferStorage(frame_buffer, sizeof(shader::FrameGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, frame_buffer, "frame");
    rebuild();
  }
  ~Impl() { glDeleteBuffers(1, &frame_buffer); }

  // The scene as the GPU and the method see it.
  const Scene& method_scene() const { return atlas_scene ? *atlas_scene : scene; }

  std::function<void(double)> step_progress(std::string_view step) const {
    if (!progress) return {};
    return [this, step](double fraction) { progress(step, fraction); };
  }

  // The method's precomputation (through the cache), then the method.
  void make_method() {
    const methods::MethodInfo& info = *methods::find_method(scene.method);
    const texture_space::SceneAtlas* atlas_ptr = atlas ? &*atlas : nullptr;
    precomputed.clear();
    if (info.precompute)
      precomputed = methods::run_precompute(*info.precompute, {method_scene(), atlas_ptr}, step_progress(info.precompute->kind)).bytes;
    method = methods::create_method({method_scene(), *scene_gpu, precomputed, atlas_ptr});
  }

  void rebuild() {
    if (scene.method.empty()) scene.method = std::string(methods::default_method().name);
    const methods::MethodInfo* info = methods::find_method(scene.method);
    if (!info) throw Error(fmt::format("{}: unknown method '{}'", scene.source, scene.method));
    check_material_maps(scene);
    if (!info->reads_material_maps) methods::refuse_material_maps(scene, *info);
    if (!info->estimates_volpath)  // a method switched to after loading: its models need what volpath does not
      for (std::size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].material)
          validate_diffusion_medium(*scene.objects[i].material,
                                    fmt::format("{}: /objects/{}/material (method '{}')", scene.source, i, scene.method));
    material_maps = has_material_maps(scene);  // a change of maps always rebuilds (classify_change)
    // Until this rebuild succeeds nothing is built: a failure leaves no method, and the next scene_changed() (the
    // caller putting the last good scene back) rebuilds whatever it is given.
    built = Scene{};
    method.reset();
    atlas.reset();
    atlas_scene.reset();
    if (info->needs_texture_atlas) {  // blob surfaces refused here, before anything reaches the GPU
      texture_space::AtlasOptions options = info->atlas_options ? info->atlas_options(scene.method_params) : texture_space::AtlasOptions{};
      std::optional<Scene> meshed;
      if (info->prepare_meshes) meshed = info->prepare_meshes(scene, step_progress("meshes"));
      const Scene& source = meshed ? *meshed : scene;
      atlas = texture_space::load_or_build_scene_atlas(source, options, step_progress("texture atlas")).atlas;
      atlas_scene = texture_space::with_atlas_meshes(source, *atlas);
    }
    scene_gpu = std::make_unique<render::SceneGpu>(method_scene(), /*model_tables=*/!info->estimates_volpath);
    geometry_dirty = true;
    environment.reset();
    if (scene.environment && scene.environment->map)
      environment = std::make_unique<render::EnvironmentTexture>(*scene.environment->map);
    make_method();
    built = scene;
    restart = true;
  }

  // After an edit that keeps the meshes: the atlas scene takes everything else from `scene` again.
  void refresh_atlas_scene() {
    if (atlas) atlas_scene = texture_space::with_atlas_meshes(scene, *atlas);
  }

  // Applies an edited scene with the least work: live parameters and materials without recreating the method
  // (and recompiling its shaders) when it accepts them, anything else by rebuilding.
  void scene_changed() {
    SceneChange change = classify_change(built, scene);
    if (change == SceneChange::Materials) check_material_maps(scene);  // an edit of a textured material's fields
    if (change != SceneChange::Rebuild) refresh_atlas_scene();
    switch (change) {
      case SceneChange::None:
        restart = true;
        break;
      case SceneChange::Live:
        if (!method->update_live_params(method_scene())) return rebuild();
        built.method_params = scene.method_params;
        restart = true;
        break;
      case SceneChange::Materials:
        if (!method->update_materials(method_scene())) {
          scene_gpu->update_materials(method_scene());
          built = Scene{};  // as in rebuild(): a failure below leaves nothing built
          method.reset();
          make_method();  // a precomputation keyed on the materials runs again
        } else {
          scene_gpu->update_materials(method_scene());
        }
        built = scene;
        restart = true;
        break;
      case SceneChange::Rebuild:
        rebuild();
        break;
    }
  }

  shader::FrameGPU frame_block(const Camera& camera) {
    shader::FrameGPU frame{};
    render::BoundingSphere bounds = scene_gpu->scene_bounds();
    float aspect = static_cast<float>(output.width) / static_cast<float>(output.height);
    frame.clip_from_world = clip_from_world(camera, aspect, bounds.radius, bounds.center);
    frame.camera_position = glm::vec4(camera.eye, 1.0f);
    frame.background = glm::vec4(scene.render.background, 0.0f);
    frame.output_size = glm::ivec4(output.width, output.height, 0, 0);
    frame.seeds.x = static_cast<unsigned>(scene.render.seed);
    frame.seeds.w = static_cast<unsigned>(scene.render.seed >> 32u);
    frame.seeds.y = static_cast<unsigned>(frame_counter);
    frame.display = glm::vec4(std::exp2(scene.render.exposure), static_cast<float>(static_cast<int>(scene.render.tonemap)),
                              0.0f, 0.0f);
    if (environment)
      frame.environment.x = LUCENT_ENVIRONMENT_MAP | (scene.environment->background ? LUCENT_ENVIRONMENT_BACKGROUND : 0);
    method->prepare_frame(frame, restart);
    return frame;
  }

  void camera_gbuffer_pass() {
    auto pass = profiler.pass("camera_gbuffer");
    output.camera_gbuffer->begin_pass();
    glUseProgram(camera_program.id());
    scene_gpu->draw_all();
    output.camera_gbuffer->bind_textures(LUCENT_TEX_CAMERA_POSITION, LUCENT_TEX_CAMERA_NORMAL, LUCENT_TEX_CAMERA_DEPTH);
    if (output.camera_gbuffer->has_uv()) output.camera_gbuffer->bind_uv(LUCENT_TEX_CAMERA_UV);
  }

  // The denoising stage over the method's radiance, when the scene enables it.
  void denoise_pass(const shader::FrameGPU& frame, const Camera& camera, bool edited) {
    const denoise::DenoiseSettings settings = denoise::denoise_settings(scene.denoise);
    const int method_frames = method->accumulated_frames();
    const bool camera_moved = frame.clip_from_world != previous_clip_from_world;
    const bool restarted = edited || camera_moved || method_frames <= previous_method_frames;
    previous_clip_from_world = frame.clip_from_world;
    previous_method_frames = method_frames;
    if (!settings.enabled) {
      denoiser.reset();
      return;
    }
    if (!denoiser || denoiser->material_maps() != material_maps)
      denoiser = std::make_unique<denoise::Denoiser>(material_maps);
    denoiser->run({frame, *output.camera_gbuffer, output.hdr, method_frames, restarted, edited, camera.fov_y_deg,
                   settings, profiler});
    denoise_history[frame_counter] = denoiser->history_frames();
  }

  void tonemap_pass() {
    auto pass = profiler.pass("tonemap");
    glBindTextureUnit(LUCENT_TEX_HDR, output.hdr);
    glBindImageTexture(LUCENT_IMAGE_LDR, output.ldr, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    glUseProgram(tonemap_program.id());
    glDispatchCompute(static_cast<GLuint>((output.width + 7) / 8), static_cast<GLuint>((output.height + 7) / 8), 1);
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }

  FrameTimings summarize(const gpu::ProfiledFrame& profiled) const {
    FrameTimings t;
    t.frame = profiled.frame;
    for (const auto& [name, ms] : profiled.passes) {
      t.passes.push_back({name, ms});
      t.total_ms += ms;
    }
    const shader::CountersGPU& c = profiled.counters;
    // Output images: RGBA32F radiance, RGBA8 display, camera G-buffer (RGBA32F + RGBA16F + DEPTH32F, + RG32F
    // texture coordinates with material maps).
    std::size_t pixels = static_cast<std::size_t>(output.width) * static_cast<std::size_t>(output.height);
    t.gpu_memory_bytes = method->gpu_memory_bytes() + pixels * (16 + 4 + 16 + 8 + 4 + (output.with_uv ? 8 : 0)) +
                         (denoiser ? denoiser->gpu_memory_bytes() : 0);
    t.stats.push_back({"translucent_pixels", static_cast<double>(c.translucent_pixels), ""});
    t.stats.push_back({"coverage", c.translucent_pixels > 0 ? static_cast<double>(c.covered_pixels) / c.translucent_pixels : 1.0, ""});
    t.stats.push_back({"gpu_memory", static_cast<double>(t.gpu_memory_bytes) / (1024.0 * 1024.0), "MiB"});
    method->statistics({t.passes, c, profiled.frame}, t.stats);
    if (auto it = denoise_history.find(profiled.frame); it != denoise_history.end())
      t.stats.push_back({"denoise_history", it->second, "frames"});
    return t;
  }

  void take_reported(bool wait) {
    for (const gpu::ProfiledFrame& f : profiler.collect(wait)) {
      latest = summarize(f);
      denoise_history.erase(denoise_history.begin(), denoise_history.upper_bound(f.frame));
      if (unclaimed.size() == kMaxUnclaimed) unclaimed.erase(unclaimed.begin());
      unclaimed.push_back(latest);
    }
  }

  void render(const Camera& camera, const RenderTarget& target) {
    if (!method)
      throw Error(fmt::format("{}: nothing to render: the scene's last rebuild failed; apply a scene that builds "
                              "(scene_changed())", scene.source));
    if (target.width <= 0 || target.height <= 0)
      throw Error(fmt::format("render target size {}x{} is empty", target.width, target.height));
    output.resize(target.width, target.height, material_maps);
    profiler.begin_frame(++frame_counter);
    const bool edited = restart;  // an edit (or a first frame) restarts the method: no history survives it
    shader::FrameGPU frame = frame_block(camera);
    restart = false;
    glNamedBufferSubData(frame_buffer, 0, sizeof(frame), &frame);
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_FRAME, frame_buffer);
    if (geometry_dirty && scene_gpu->animated()) scene_gpu->update(time_seconds, &profiler);
    geometry_dirty = false;
    scene_gpu->bind_buffers();
    if (environment) environment->bind();
    camera_gbuffer_pass();
    method->render({method_scene(), *scene_gpu, *output.camera_gbuffer, output.hdr, profiler, frame.seeds.z != 0, time_seconds,
                    frame_counter});
    denoise_pass(frame, camera, edited);
    tonemap_pass();
    glBlitNamedFramebuffer(output.ldr_framebuffer, target.framebuffer, 0, 0, output.width, output.height, 0, 0,
                           target.width, target.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    profiler.end_frame();
    take_reported(/*wait=*/false);
  }
};

Renderer::Renderer(Scene scene, RenderProgress progress)
    : impl_(std::make_unique<Impl>(std::move(scene), std::move(progress))) {}
Renderer::~Renderer() = default;

void Renderer::render(const Camera& camera, const RenderTarget& target) { impl_->render(camera, target); }
Scene& Renderer::scene() { return impl_->scene; }
const Scene& Renderer::scene() const { return impl_->scene; }
void Renderer::scene_changed() { impl_->scene_changed(); }
void Renderer::set_time(double seconds) {
  if (seconds == impl_->time_seconds) return;
  impl_->time_seconds = seconds;
  if (impl_->scene_gpu->animated()) impl_->geometry_dirty = true, impl_->restart = true;
}
double Renderer::time() const { return impl_->time_seconds; }
void Renderer::restart() { impl_->restart = true; }
int Renderer::accumulated_frames() const { return impl_->method ? impl_->method->accumulated_frames() : 0; }
const FrameTimings& Renderer::timings() const { return impl_->latest; }
std::vector<FrameTimings> Renderer::finished_frames(bool wait) {
  impl_->take_reported(wait);
  return std::exchange(impl_->unclaimed, {});
}
const FrameTimings& Renderer::last_frame_timings() {
  impl_->take_reported(/*wait=*/true);
  return impl_->latest;
}

double FrameTimings::stat(std::string_view name, double fallback) const {
  for (const FrameStatistic& s : stats)
    if (s.name == name) return s.value;
  return fallback;
}

double FrameTimings::pass_ms(std::string_view name) const {
  for (const PassTiming& p : passes)
    if (p.name == name) return p.ms;
  return 0.0;
}
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
