// radiosity_maps.cpp: the three passes of the scattered-radiosity-maps method (see radiosity_maps.h).
#include "methods/radiosity_maps/radiosity_maps.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include <fmt/format.h>

#include "gpu/frame_counters.h"
#include "gpu/gl_debug.h"
#include "gpu/shader_program.h"
#include "platform/gl_capabilities.h"
#include "lucent/error.h"
#include "render/light_gbuffer.h"

namespace lucent::methods {
namespace {

using shader::FrameGPU;
using shader::LightGPU;
using shader::ViewGPU;

// Defaults follow Dal Corso et al. 2015, Section 5 (512x512 maps and light map, K = 16) and lucent's
// benchmark configuration (N = 32 per band).
constexpr ParamDecl kParams[] = {
    {"K", ParamType::Int, "16", "maps", 1, LUCENT_MAX_MAPS, "", "number of scattered-radiosity maps (views)"},
    {"directions", ParamType::Enum, "\"halton\"", "", 0, 0, "halton|fibonacci",
     "automatic map directions: Halton points (the paper) or a spherical Fibonacci set (more even)"},
    {"map_directions", ParamType::Vec3List, "[]", "", -1e9, 1e9, "",
     "user map directions (from the object toward each map camera); non-empty: overrides K and directions"},
    {"N", ParamType::Int, "32", "samples", 1, 4096, "", "samples per colour band per map texel per frame"},
    {"map_size", ParamType::Int, "512", "texels", 8, 4096, "", "resolution of each scattered-radiosity map"},
    {"light_map_size", ParamType::Int, "512", "texels", 8, 8192, "", "resolution of each light G-buffer layer"},
    {"eps_bias", ParamType::Float, "2.0", "map texels", 0, 64, "", "visibility depth bias of Algorithm 1"},
    {"eps_comb", ParamType::Float, "1.0", "map texels", 0, 64, "", "offset of x_o along -n_o (Algorithm 1)"},
    {"visibility_taps", ParamType::Int, "3", "taps/axis", 1, 7, "", "multi-sampled visibility: taps per axis"},
    {"filter_lod", ParamType::Float, "0.0", "mip level", 0, 4, "", "mip level read from the maps (noise filter)"},
    {"progressive", ParamType::Bool, "true", "", 0, 1, "", "accumulate maps over frames while only the camera moves"},
    {"specular", ParamType::Bool, "true", "", 0, 1, "", "add GGX specular reflection of the lights"},
    {"roughness", ParamType::Float, "0.15", "GGX alpha", 0.01, 1, "", "roughness of the specular reflection"},
    {"vpls", ParamType::Int, "64", "VPLs", 0, 4096, "", "virtual point lights carrying emergent light to diffuse objects (0: off)"},
    {"vpl_map_size", ParamType::Int, "256", "texels", 8, 4096, "", "resolution of each face of the VPL placement cube map"},
    {"view", ParamType::Enum, "\"shaded\"", "", 0, 0, "shaded|coverage", "debug view: coverage shows unmapped areas in magenta"},
};

float radical_inverse(int index, int base) {
  float inv_base = 1.0f / static_cast<float>(base), fraction = inv_base, result = 0.0f;
  for (int i = index; i > 0; i /= base, fraction *= inv_base) result += static_cast<float>(i % base) * fraction;
  return result;
}

GLuint make_radiosity_texture(int size, int layers) {
  GLuint texture = 0;
  int levels = 1 + static_cast<int>(std::floor(std::log2(static_cast<float>(size))));
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture);
  glTextureStorage3D(texture, levels, GL_RGBA32F, size, size, layers);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gpu::label_object(GL_TEXTURE, texture, "scattered radiosity maps");
  return texture;
}

// The maps and their G-buffer grow as map_size^2 K: too much is refused before anything is allocated, naming the
// parameters, since a failed allocation shows only later as an incomplete framebuffer (on llvmpipe: the OOM killer).
const ParamValues& with_memory_checked(const ParamValues& params) {
  const auto size = static_cast<std::uint64_t>(params.integer("map_size"));
  const auto K = static_cast<std::uint64_t>(params.integer("K"));
  // G-buffer RGBA32F + RGBA16F + DEPTH32F per texel, and the RGBA32F maps with their mip chain (4/3).
  const std::uint64_t bytes = size * size * K * (16 + 8 + 4) + size * size * K * 16 * 4 / 3;
  platform::require_device_memory(bytes, "the scattered-radiosity maps and their G-buffer");
  return params;
}

class RadiosityMaps final : public Method {
 public:
  RadiosityMaps(const Scene& scene, const render::SceneGpu& scene_gpu) try
      : params_(with_memory_checked(scene.method_params)),
        map_directions_(choose_map_directions(scene)),
        K_(static_cast<int>(map_directions_.size())),
        map_size_(params_.integer("map_size")),
        light_map_size_(params_.integer("light_map_size")),
        light_gbuffer_(scene, scene_gpu, light_map_size_),
        map_gbuffer_(map_size_, map_size_, K_, "radiosity-map G-buffer"),
        vpl_count_(params_.integer("vpls")),
        vpl_map_size_(params_.integer("vpl_map_size")),
        vpl_gbuffer_(vpl_count_ > 0 ? vpl_map_size_ : 1, vpl_count_ > 0 ? vpl_map_size_ : 1, 6, "VPL cube map"),
        gbuffer_program_(gpu::ShaderProgram::graphics("gbuffer/gbuffer.vert", "gbuffer/layered_views.geom",
                                                      "gbuffer/gbuffer.frag")),
        integrate_program_(gpu::ShaderProgram::compute("radiosity_maps/integrate.comp", render::light_sampling_defines(scene))),
        combine_program_(gpu::ShaderProgram::compute("radiosity_maps/combine.comp")),
        vpl_program_(gpu::ShaderProgram::compute("radiosity_maps/vpl.comp")),
        probe_program_(gpu::ShaderProgram::compute("radiosity_maps/probe.comp")) {
    radiosity_ = make_radiosity_texture(map_size_, K_);
    glCreateBuffers(1, &vpl_buffer_);
    glNamedBufferStorage(vpl_buffer_, static_cast<GLsizeiptr>(sizeof(shader::VplGPU)) * std::max(1, vpl_count_), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, vpl_buffer_, "virtual point lights");
    build_views(scene_gpu);
    warn_about_pearling(scene);
    warn_about_low_albedo(scene);
  } catch (const Error& e) {
    // A driver's refusal (out of memory, an incomplete framebuffer) named with the parameters that size the buffers.
    const ParamValues& p = scene.method_params;
    throw Error(fmt::format("method.map_size {}, method.K {}, method.light_map_size {}, method.vpl_map_size {}: {}",
                            p.integer("map_size"), p.integer("K"), p.integer("light_map_size"),
                            p.integer("vpl_map_size"), e.what()));
  }

  ~RadiosityMaps() override {
    glDeleteTextures(1, &radiosity_);
    glDeleteBuffers(1, &vpl_buffer_);
  }

  void prepare_frame(FrameGPU& frame, bool restart) override {
    restart = restart || !params_.boolean("progressive");
    accumulated_ = restart ? 1 : accumulated_ + 1;
    frame.counts = glm::ivec4(0, K_, params_.integer("N"), params_.integer("visibility_taps"));
    light_gbuffer_.fill_frame(frame);
    frame.sizes.x = map_size_;
    frame.seeds.z = restart ? 1u : 0u;
    frame.biases = glm::vec4(params_.number("eps_bias"), params_.number("eps_comb"), params_.number("filter_lod"),
                             params_.number("roughness"));
    frame.options.y = params_.text("view") == "coverage" ? LUCENT_VIEW_COVERAGE : LUCENT_VIEW_SHADED;
    frame.options.z = params_.boolean("specular") ? 1.0f : 0.0f;
    frame.extra_counts.y = vpl_count_;
    frame.extra_counts.z = vpl_map_size_;
    frame.vpl_center = glm::vec4(vpl_center_, 0.0f);
    std::copy(vpl_views_.begin(), vpl_views_.end(), frame.vpl_views);
    std::copy(maps_.begin(), maps_.end(), frame.maps);
  }

  void render(const FrameContext& context) override {
    light_gbuffer_.render(context.scene_gpu, context.timer);
    render_map_gbuffers(context);
    integrate(context);
    generate_mipmaps(context);
    place_vpls(context);
    combine(context);
  }

  int accumulated_frames() const override { return accumulated_; }
  glm::uvec2 pixel_coverage() const override {
    shader::CountersGPU c = counters_.read();
    return {c.translucent_pixels, c.covered_pixels};
  }

  std::size_t gpu_memory_bytes() const override {
    auto layers = [](const gpu::GBuffer& g) { return static_cast<std::size_t>(std::max(1, g.layers())); };
    auto gbuffer = [&](const gpu::GBuffer& g) {  // RGBA32F position + RGBA16F normal + DEPTH32F
      return static_cast<std::size_t>(g.size_x()) * static_cast<std::size_t>(g.size_y()) * layers(g) * (16 + 8 + 4);
    };
    std::size_t maps = static_cast<std::size_t>(map_size_) * static_cast<std::size_t>(map_size_) *
                       static_cast<std::size_t>(K_) * 16 * 4 / 3;  // RGBA32F with its mip chain
    return light_gbuffer_.gpu_memory_bytes() + gbuffer(map_gbuffer_) + (vpl_count_ > 0 ? gbuffer(vpl_gbuffer_) : 0) + maps +
           sizeof(shader::VplGPU) * static_cast<std::size_t>(vpl_count_);
  }

  std::vector<shader::ProbeGPU> scattered_radiosity(std::vector<shader::ProbeGPU> probes) const override {
    if (probes.empty()) return probes;
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(probes.size() * sizeof(shader::ProbeGPU)), probes.data(),
                         GL_DYNAMIC_STORAGE_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_PROBES, buffer);
    bind_map_textures();
    glUseProgram(probe_program_.id());
    glUniform1i(glGetUniformLocation(probe_program_.id(), "u_count"), static_cast<GLint>(probes.size()));
    glDispatchCompute(static_cast<GLuint>((probes.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(probes.size() * sizeof(shader::ProbeGPU)), probes.data());
    glDeleteBuffers(1, &buffer);
    return probes;
  }

  std::vector<shader::VplGPU> virtual_point_lights() const override {
    std::vector<shader::VplGPU> vpls(static_cast<std::size_t>(vpl_count_));
    if (!vpls.empty())
      glGetNamedBufferSubData(vpl_buffer_, 0, static_cast<GLsizeiptr>(vpls.size() * sizeof(shader::VplGPU)), vpls.data());
    return vpls;
  }
  std::uint64_t bssrdf_samples_last_frame() const override {
    return static_cast<std::uint64_t>(counters_.read().covered_texels) * 3u * static_cast<std::uint64_t>(params_.integer("N")) *
           static_cast<std::uint64_t>(light_gbuffer_.light_count());
  }

 private:
  // The user's directions (normalized; checked here because the scene parser does not know the method's
  // meaning), or K automatic ones.
  std::vector<glm::vec3> choose_map_directions(const Scene& scene) const {
    const std::vector<glm::vec3>& user = params_.vec3_list("map_directions");
    if (user.empty()) {
      int K = params_.integer("K");
      return params_.text("directions") == "fibonacci" ? fibonacci_sphere_directions(K) : halton_sphere_directions(K);
    }
    if (user.size() > LUCENT_MAX_MAPS)
      throw Error(fmt::format("{}: /method/map_directions: {} directions; at most {}", scene.source, user.size(),
                              LUCENT_MAX_MAPS));
    std::vector<glm::vec3> out;
    for (std::size_t i = 0; i < user.size(); ++i) {
      float length = glm::length(user[i]);
      if (!(length > 1e-6f))
        throw Error(fmt::format("{}: /method/map_directions/{}: must be a non-zero vector", scene.source, i));
      out.push_back(user[i] / length);
    }
    return out;
  }

  // Dal Corso et al., Section 5: when the scattering length 1/sigma_tr is under about two light-map texels the
  // contributions cluster ("pearling"). Say so once, with the light-map size that would avoid it.
  void warn_about_pearling(const Scene& scene) const {
    if (scene.lights.empty()) return;
    float texel_mm = light_gbuffer_.views().views[0].direction.w / static_cast<float>(light_map_size_) * scene.scale_mm;
    for (const SceneObject& object : scene.objects) {
      if (!object.material) continue;
      glm::vec3 sigma_tr = object.material->sigma_tr();
      float length_mm = 1.0f / std::max({sigma_tr.x, sigma_tr.y, sigma_tr.z});
      if (length_mm >= 2.0f * texel_mm) continue;
      std::fprintf(stderr,
                   "lucent: warning: %s: scattering length %.3g mm is under 2 light-map texels (%.3g mm each); "
                   "expect pearling, or raise method.light_map_size to %d\n",
                   object.name.c_str(), length_mm, texel_mm,
                   static_cast<int>(std::ceil(2.0f * texel_mm / length_mm * static_cast<float>(light_map_size_))));
    }
  }

  // Diffusion models assume scattering dominates absorption. Far from that (reduced albedo well under 1/2 in some
  // band) the dipoles give implausible colours, e.g. Strawberry Shampoo, whose alpha' is 0.01 / 0.003 / 0.0002.
  static void warn_about_low_albedo(const Scene& scene) {
    for (const SceneObject& object : scene.objects) {
      if (!object.material) continue;
      glm::vec3 s = object.material->sigma_s_prime();
      glm::vec3 alpha_prime = s / (s + object.material->sigma_a);
      float lowest = std::min({alpha_prime.x, alpha_prime.y, alpha_prime.z});
      if (lowest >= 0.3f) continue;
      std::fprintf(stderr,
                   "lucent: warning: %s: reduced albedo alpha' = (%.3g, %.3g, %.3g); the diffusion models are far "
                   "outside their validity below about 0.3 and colours may be implausible\n",
                   object.name.c_str(), alpha_prime.x, alpha_prime.y, alpha_prime.z);
    }
  }

  void build_views(const render::SceneGpu& scene_gpu) {
    render::BoundingSphere object = scene_gpu.translucent_bounds();
    float half_width = 1.02f * object.radius + 1e-6f;
    // Step 2 views: K directions from a Halton sequence on the bounding sphere, looking at its centre.
    for (glm::vec3 d : map_directions_) {
      ViewGPU view = render::orthographic_view(object.center, d, half_width, half_width, 2.0f * half_width);
      view.direction = glm::vec4(d, 2.0f * half_width);  // a map's direction points toward its camera (d_k)
      maps_.push_back(view);
    }
    // The VPL cube map about the translucent objects' centre (the paper uses the bounding box centre).
    vpl_center_ = object.center;
    render::append_cube_views(vpl_views_, vpl_center_, 1e-4f * half_width, 2.0f * half_width, vpl_map_size_);
  }

  void render_map_gbuffers(const FrameContext& context) {
    gpu::DebugGroup group("map_gbuffers");
    context.timer.begin("map_gbuffers");
    map_gbuffer_.begin_pass();
    glUseProgram(gbuffer_program_.id());
    glUniform1i(glGetUniformLocation(gbuffer_program_.id(), "u_view_set"), 1);
    context.scene_gpu.draw_translucent();
    context.timer.end();
  }

  void integrate(const FrameContext& context) {
    gpu::DebugGroup group("integrate");
    context.timer.begin("integrate");
    counters_.reset_and_bind();
    map_gbuffer_.bind_textures(LUCENT_TEX_MAP_POSITION, LUCENT_TEX_MAP_NORMAL, LUCENT_TEX_MAP_DEPTH);
    light_gbuffer_.bind_textures();
    glBindImageTexture(LUCENT_IMAGE_RADIOSITY, radiosity_, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
    glUseProgram(integrate_program_.id());
    auto groups = static_cast<GLuint>((map_size_ + 7) / 8);
    glDispatchCompute(groups, groups, static_cast<GLuint>(K_));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT);
    context.timer.end();
  }

  void bind_map_textures() const {
    map_gbuffer_.bind_textures(LUCENT_TEX_MAP_POSITION, LUCENT_TEX_MAP_NORMAL, LUCENT_TEX_MAP_DEPTH);
    glBindTextureUnit(LUCENT_TEX_RADIOSITY, radiosity_);
  }

  // Section 3.4: VPLs on the outermost surface (cube map, farthest depth), their radiosity from the maps.
  void place_vpls(const FrameContext& context) {
    if (vpl_count_ == 0) return;
    gpu::DebugGroup group("vpls");
    context.timer.begin("vpls");
    vpl_gbuffer_.begin_pass(/*farthest=*/true);
    glUseProgram(gbuffer_program_.id());
    glUniform1i(glGetUniformLocation(gbuffer_program_.id(), "u_view_set"), 2);
    context.scene_gpu.draw_translucent();
    glDepthFunc(GL_LESS);
    vpl_gbuffer_.bind_textures(LUCENT_TEX_VPL_POSITION, LUCENT_TEX_VPL_NORMAL, LUCENT_TEX_VPL_DEPTH);
    bind_map_textures();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_VPLS, vpl_buffer_);
    glUseProgram(vpl_program_.id());
    glDispatchCompute(static_cast<GLuint>((vpl_count_ + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    context.timer.end();
  }

  void generate_mipmaps(const FrameContext& context) {
    gpu::DebugGroup group("mipmaps");
    context.timer.begin("mipmaps");
    glGenerateTextureMipmap(radiosity_);
    context.timer.end();
  }

  void combine(const FrameContext& context) {
    gpu::DebugGroup group("combine");
    context.timer.begin("combine");
    bind_map_textures();
    light_gbuffer_.bind_textures();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_VPLS, vpl_buffer_);
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUseProgram(combine_program_.id());
    int width = context.camera_gbuffer.size_x(), height = context.camera_gbuffer.size_y();
    glDispatchCompute(static_cast<GLuint>((width + 7) / 8), static_cast<GLuint>((height + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    GL_SHADER_STORAGE_BARRIER_BIT);  // counters read back or cleared next
    context.timer.end();
  }

  const ParamValues& params_;
  std::vector<glm::vec3> map_directions_;
  int K_, map_size_, light_map_size_;
  int accumulated_ = 0;
  render::LightGBuffer light_gbuffer_;
  gpu::GBuffer map_gbuffer_;
  int vpl_count_, vpl_map_size_;
  gpu::GBuffer vpl_gbuffer_;
  gpu::ShaderProgram gbuffer_program_, integrate_program_, combine_program_, vpl_program_, probe_program_;
  GLuint radiosity_ = 0, vpl_buffer_ = 0;
  gpu::FrameCounters counters_;
  std::vector<ViewGPU> maps_, vpl_views_;
  glm::vec3 vpl_center_{0.0f};
};

}  // namespace

std::span<const ParamDecl> radiosity_maps_params() { return kParams; }

std::unique_ptr<Method> create_radiosity_maps(const Scene& scene, const render::SceneGpu& scene_gpu) {
  return std::make_unique<RadiosityMaps>(scene, scene_gpu);
}

std::vector<glm::vec3> fibonacci_sphere_directions(int count) {
  std::vector<glm::vec3> directions;
  for (int i = 0; i < count; ++i) {
    float z = 1.0f - (2.0f * static_cast<float>(i) + 1.0f) / static_cast<float>(count);
    float phi = 2.39996322972865f * static_cast<float>(i);  // golden angle
    float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    directions.emplace_back(s * std::cos(phi), s * std::sin(phi), z);
  }
  return directions;
}

std::vector<glm::vec3> halton_sphere_directions(int count) {
  std::vector<glm::vec3> directions;
  for (int i = 1; i <= count; ++i) {
    float z = 1.0f - 2.0f * radical_inverse(i, 2);
    float phi = 2.0f * 3.14159265f * radical_inverse(i, 3);
    float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    directions.emplace_back(s * std::cos(phi), s * std::sin(phi), z);
  }
  return directions;
}

}  // namespace lucent::methods
