// radiosity_maps.cpp: the three passes of the scattered-radiosity-maps method (see radiosity_maps.h).
#include "methods/radiosity_maps/radiosity_maps.h"

#include "methods/method.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "gpu/layer_views.h"
#include "gpu/shader_program.h"
#include "methods/radiosity_maps/pearling_warning.h"
#include "methods/radiosity_maps/radiosity_maps_io.h"
#include "platform/gl_capabilities.h"
#include "lucent/warning.h"
#include "lucent/error.h"
#include "materials/material_maps.h"
#include "render/light_gbuffer.h"

namespace lucent::methods {
namespace {

using shader::FrameGPU;
using shader::LightGPU;
using shader::RadiosityMapsGPU;
using shader::ViewGPU;

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
        map_gbuffer_(map_size_, map_size_, K_, "radiosity-map G-buffer", has_material_maps(scene)),
        vpl_count_(params_.integer("vpls")),
        vpl_map_size_(params_.integer("vpl_map_size")),
        vpl_gbuffer_(vpl_count_ > 0 ? vpl_map_size_ : 1, vpl_count_ > 0 ? vpl_map_size_ : 1, 6, "VPL cube map"),
        gbuffer_program_(gpu::layered_gbuffer_program()),
        integrate_program_(gpu::ShaderProgram::compute("methods/radiosity_maps/shaders/integrate.comp", render::light_sampling_defines(scene))),
        combine_program_(gpu::ShaderProgram::compute("methods/radiosity_maps/shaders/combine.comp")),
        vpl_program_(gpu::ShaderProgram::compute("methods/radiosity_maps/shaders/vpl.comp")),
        probe_program_(gpu::ShaderProgram::compute("methods/radiosity_maps/shaders/probe.comp")) {
    iterations_per_sample_ = render::light_sampling_iterations_per_sample(scene);
    radiosity_ = make_radiosity_texture(map_size_, K_);
    glCreateBuffers(1, &vpl_buffer_);
    glNamedBufferStorage(vpl_buffer_, static_cast<GLsizeiptr>(sizeof(shader::VplGPU)) * std::max(1, vpl_count_), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, vpl_buffer_, "virtual point lights");
    build_views(scene_gpu);
    map_layers_ = std::make_unique<gpu::LayerViews>(maps_, "radiosity map views");
    vpl_layers_ = std::make_unique<gpu::LayerViews>(vpl_views_, "VPL cube-map views");
    glCreateBuffers(1, &block_buffer_);
    glNamedBufferStorage(block_buffer_, sizeof(RadiosityMapsGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, block_buffer_, "radiosity-maps block");
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
    glDeleteBuffers(1, &block_buffer_);
  }

  void prepare_frame(FrameGPU& frame, bool restart) override {
    restart = restart || !params_.boolean("progressive");
    const int converged_after = params_.integer("converged_after");
    if (restart) {
      accumulated_ = 1, converged_ = false, vpls_placed_ = false;
    } else if (converged_after > 0 && accumulated_ >= converged_after) {
      converged_ = true;  // Section 3.2: the maps are final; only step 3 runs
    } else {
      ++accumulated_;
    }
    light_gbuffer_.fill_frame(frame);
    render::check_light_sampling_loops("radiosity-maps", frame.light_counts.x, static_cast<std::uint64_t>(params_.integer("N")),
                                       iterations_per_sample_);
    frame.light_counts.w = params_.integer("visibility_taps");
    frame.seeds.z = restart ? 1u : 0u;
    const bool coverage_view = params_.text("view") == "coverage";
    frame.shading = glm::vec4(params_.boolean("specular") && !coverage_view ? 1.0f : 0.0f,
                              params_.number("roughness"), 0.0f, 0.0f);
    RadiosityMapsGPU block{};
    block.counts = glm::ivec4(K_, params_.integer("N"), map_size_, coverage_view ? LUCENT_VIEW_COVERAGE : LUCENT_VIEW_SHADED);
    block.biases = glm::vec4(params_.number("eps_bias"), params_.number("eps_comb"), params_.number("filter_lod"), 0.0f);
    block.vpls = glm::ivec4(vpl_count_, vpl_map_size_, params_.integer("visibility_taps"), 0);
    block.vpl_center = glm::vec4(vpl_center_, 0.0f);
    std::copy(maps_.begin(), maps_.end(), block.maps);
    std::copy(vpl_views_.begin(), vpl_views_.end(), block.vpl_views);
    glNamedBufferSubData(block_buffer_, 0, sizeof(block), &block);
  }

  void render(const FrameContext& context) override {
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_METHOD, block_buffer_);
    const float lod = static_cast<float>(params_.number("filter_lod"));
    if (!converged_) {
      light_gbuffer_.render(context.scene_gpu, context.profiler);
      render_map_gbuffers(context);
      integrate(context);
      mipmaps_built_ = false;
      vpls_placed_ = false;
    }
    // Only Algorithm 1 with a filter_lod above 0 reads the mip chain.
    if (lod > 0.0f && !mipmaps_built_) {
      generate_mipmaps(context);
      mipmaps_built_ = converged_;
      vpls_placed_ = false;
    }
    // VPL radiosity comes from the maps: once they are converged it is placed once more and kept.
    if (vpl_count_ > 0 && !(converged_ && vpls_placed_ && vpl_lod_ == lod)) {
      place_vpls(context);
      vpls_placed_ = converged_;
      vpl_lod_ = lod;
    }
    combine(context);
  }

  int accumulated_frames() const override { return accumulated_; }

  void statistics(const FrameRecord& record, std::vector<FrameStatistic>& out) const override {
    const double samples = static_cast<double>(record.counters.method_counts[0]) * 3.0 * params_.integer("N") *
                           light_gbuffer_.light_count();
    const double integrate_ms = record.pass_ms("integrate");
    out.push_back({"bssrdf_samples", samples, ""});
    out.push_back({"bssrdf_samples_per_second", integrate_ms > 0.0 ? samples / (integrate_ms * 1e-3) : 0.0, "1/s"});
    out.push_back({"covered_texels", static_cast<double>(record.counters.method_counts[0]), ""});
    out.push_back({"maps", static_cast<double>(K_), ""});
    out.push_back({"vpls", static_cast<double>(vpl_count_), ""});
    out.push_back({"converged", !record.ran("integrate") ? 1.0 : 0.0, ""});
  }

  // N, the biases, taps, filter, specular, view and converged_after are read every frame.
  bool update_live_params(const Scene& scene) override {
    (void)scene;
    return true;
  }
  // Materials are read from the scene's material buffer by every pass: a restart is all a change needs.
  bool update_materials(const Scene& scene) override {
    warn_about_low_albedo(scene);
    iterations_per_sample_ = render::light_sampling_iterations_per_sample(scene);
    return true;
  }

  std::size_t gpu_memory_bytes() const override {
    auto layers = [](const gpu::GBuffer& g) { return static_cast<std::size_t>(std::max(1, g.layers())); };
    auto gbuffer = [&](const gpu::GBuffer& g) {  // RGBA32F position + RGBA16F normal + DEPTH32F (+ RG32F uv)
      return static_cast<std::size_t>(g.size_x()) * static_cast<std::size_t>(g.size_y()) * layers(g) *
             (16 + 8 + 4 + (g.has_uv() ? 8 : 0));
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

  // Dal Corso et al., Section 5: contributions cluster ("pearling") when the scattering length is under about two
  // light-map texels. Say so once per object (pearling_warning.h).
  void warn_about_pearling(const Scene& scene) const {
    if (scene.lights.empty()) return;
    float texel_mm = light_gbuffer_.views().views[0].direction.w / static_cast<float>(light_map_size_) * scene.scale_mm;
    int max_light_map_size = light_map_size_;
    for (const ParamDecl& p : find_method("radiosity-maps")->params)
      if (p.name == "light_map_size") max_light_map_size = static_cast<int>(p.max);
    for (const SceneObject& object : scene.objects) {
      if (!object.material) continue;
      glm::vec3 sigma_tr = densest_darkest(*object.material).sigma_tr();  // a textured material's densest texel
      float length_mm = 1.0f / std::max({sigma_tr.x, sigma_tr.y, sigma_tr.z});
      const std::string warning =
          pearling_warning(object.name, length_mm, texel_mm, light_map_size_, max_light_map_size);
      if (!warning.empty()) warn(warning);
    }
  }

  // Diffusion models assume scattering dominates absorption. Far from that (reduced albedo well under 1/2 in some
  // band) the dipoles give implausible colours, e.g. Strawberry Shampoo, whose alpha' is 0.01 / 0.003 / 0.0002.
  static void warn_about_low_albedo(const Scene& scene) {
    for (const SceneObject& object : scene.objects) {
      if (!object.material) continue;
      const Material m = densest_darkest(*object.material);  // a textured material's darkest texel
      glm::vec3 s = m.sigma_s_prime();
      glm::vec3 alpha_prime = s / (s + m.sigma_a);
      float lowest = std::min({alpha_prime.x, alpha_prime.y, alpha_prime.z});
      if (lowest >= 0.3f) continue;
      warn(fmt::format("{}: reduced albedo alpha' = ({:.3g}, {:.3g}, {:.3g}); the diffusion models are far "
                       "outside their validity below about 0.3 and colours may be implausible",
                       object.name, alpha_prime.x, alpha_prime.y, alpha_prime.z));
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
    auto pass = context.profiler.pass("map_gbuffers");
    map_layers_->bind();
    map_gbuffer_.begin_pass();
    glUseProgram(gbuffer_program_.id());
    context.scene_gpu.draw_translucent(static_cast<int>(map_layers_->count()));
  }

  void integrate(const FrameContext& context) {
    auto pass = context.profiler.pass("integrate");
    map_gbuffer_.bind_textures(LUCENT_TEX_MAP_POSITION, LUCENT_TEX_MAP_NORMAL, LUCENT_TEX_MAP_DEPTH);
    if (map_gbuffer_.has_uv()) map_gbuffer_.bind_uv(LUCENT_TEX_MAP_UV);
    light_gbuffer_.bind_textures();
    glBindImageTexture(LUCENT_IMAGE_RADIOSITY, radiosity_, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
    glUseProgram(integrate_program_.id());
    auto groups = static_cast<GLuint>((map_size_ + 7) / 8);
    glDispatchCompute(groups, groups, static_cast<GLuint>(K_));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT);
  }

  void bind_map_textures() const {
    map_gbuffer_.bind_textures(LUCENT_TEX_MAP_POSITION, LUCENT_TEX_MAP_NORMAL, LUCENT_TEX_MAP_DEPTH);
    glBindTextureUnit(LUCENT_TEX_RADIOSITY, radiosity_);
  }

  // Section 3.4: VPLs on the outermost surface (cube map, farthest depth), their radiosity from the maps.
  void place_vpls(const FrameContext& context) {
    auto pass = context.profiler.pass("vpls");
    vpl_layers_->bind();
    vpl_gbuffer_.begin_pass(/*farthest=*/true);
    glUseProgram(gbuffer_program_.id());
    context.scene_gpu.draw_translucent(static_cast<int>(vpl_layers_->count()));
    glDepthFunc(GL_LESS);
    vpl_gbuffer_.bind_textures(LUCENT_TEX_VPL_POSITION, LUCENT_TEX_VPL_NORMAL, LUCENT_TEX_VPL_DEPTH);
    bind_map_textures();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_VPLS, vpl_buffer_);
    glUseProgram(vpl_program_.id());
    glDispatchCompute(static_cast<GLuint>((vpl_count_ + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }

  void generate_mipmaps(const FrameContext& context) {
    auto pass = context.profiler.pass("mipmaps");
    glGenerateTextureMipmap(radiosity_);
  }

  void combine(const FrameContext& context) {
    auto pass = context.profiler.pass("combine");
    bind_map_textures();
    light_gbuffer_.bind_textures();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_VPLS, vpl_buffer_);
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUseProgram(combine_program_.id());
    int width = context.camera_gbuffer.size_x(), height = context.camera_gbuffer.size_y();
    glDispatchCompute(static_cast<GLuint>((width + 7) / 8), static_cast<GLuint>((height + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    GL_SHADER_STORAGE_BARRIER_BIT);  // counters read back or cleared next
  }

  const ParamValues& params_;
  std::vector<glm::vec3> map_directions_;
  int K_, map_size_, light_map_size_;
  int accumulated_ = 0;
  render::LightGBuffer light_gbuffer_;
  std::uint64_t iterations_per_sample_ = 1;  // shader loop iterations per BSSRDF sample (check_loop_iterations)
  gpu::GBuffer map_gbuffer_;
  int vpl_count_, vpl_map_size_;
  gpu::GBuffer vpl_gbuffer_;
  gpu::ShaderProgram gbuffer_program_, integrate_program_, combine_program_, vpl_program_, probe_program_;
  GLuint radiosity_ = 0, vpl_buffer_ = 0;
  std::vector<ViewGPU> maps_, vpl_views_;
  std::unique_ptr<gpu::LayerViews> map_layers_, vpl_layers_;
  GLuint block_buffer_ = 0;
  glm::vec3 vpl_center_{0.0f};
  bool converged_ = false;      // the maps are final: steps 1-2 are skipped (converged mode)
  bool mipmaps_built_ = false;  // the mip chain matches the converged maps
  bool vpls_placed_ = false;    // the VPLs match the converged maps
  float vpl_lod_ = -1.0f;       // filter_lod the VPLs were placed with
};

}  // namespace

std::unique_ptr<Method> create_radiosity_maps(const MethodSetup& setup) {
  return std::make_unique<RadiosityMaps>(setup.scene, setup.scene_gpu);
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
