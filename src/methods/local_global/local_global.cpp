// local_global.cpp: the GPU side of the local-global method (Lensch, Goesele, Bekaert, Kautz, Magnor, Lang,
// Seidel, "Interactive Rendering of Translucent Objects", Pacific Graphics 2002, Section 6) on the tables of
// local_global_precompute.h: per frame the illumination map (F_t E per atlas texel, shadowed), the vertex
// irradiance and direct radiosity (a gather over each vertex's texels), the sparse global product, the 7 x 7
// local kernels, a camera view of the meshes' atlas coordinates and interpolated vertex radiosity, and the
// per-pixel combination L = F_t / pi (B_l + B^d + B^g'). Rigid objects only.
#include "methods/method.h"

#include <algorithm>
#include <string>
#include <cstring>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "gpu/image_texture.h"
#include "gpu/screen_targets.h"
#include "gpu/shader_program.h"
#include "lucent/error.h"
#include "methods/local_global/local_global_io.h"
#include "methods/local_global/local_global_precompute.h"
#include "platform/gl_capabilities.h"
#include "render/light_gbuffer.h"
#include "texture_space/texture_gbuffer.h"

namespace lucent::methods {
namespace {

namespace lg = local_global;

std::string defines(const Scene& scene) {
  return render::light_sampling_defines(scene) +
         fmt::format("#define LG_TEX_POSITION {}\n#define LG_TEX_NORMAL_RATIO {}\n", texture_space::kTexturePosition,
                     texture_space::kTextureNormalRatio);
}

template <typename T>
GLuint make_buffer(const std::vector<T>& data, const std::string& label, std::size_t& bytes) {
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  const std::size_t size = std::max<std::size_t>(16, data.size() * sizeof(T));
  glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(size), data.empty() ? nullptr : data.data(), 0);
  gpu::label_object(GL_BUFFER, buffer, label);
  if (glGetError() == GL_OUT_OF_MEMORY)
    throw Error(fmt::format("local-global: out of GPU memory for {} ({:.1f} MiB)", label, static_cast<double>(size) / 1048576.0));
  bytes += size;
  return buffer;
}

GLuint make_empty_buffer(std::size_t size, const std::string& label, std::size_t& bytes) {
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  size = std::max<std::size_t>(16, size);
  glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(size), nullptr, 0);
  gpu::label_object(GL_BUFFER, buffer, label);
  bytes += size;
  return buffer;
}

std::uint32_t float_bits(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof(u));
  return u;
}

class LocalGlobal final : public Method {
 public:
  LocalGlobal(const Scene& scene, const render::SceneGpu& scene_gpu, const texture_space::SceneAtlas& atlas,
              std::span<const std::byte> precomputed)
      : params_(scene.method_params),
        data_(lg::decode(precomputed)),
        light_gbuffer_(scene, scene_gpu, params_.integer("light_map_size")),
        texture_gbuffer_(scene_gpu, atlas),
        illumination_program_(gpu::ShaderProgram::compute("methods/local_global/shaders/illumination.comp", defines(scene))),
        vertex_program_(gpu::ShaderProgram::compute("methods/local_global/shaders/vertex_irradiance.comp")),
        vertex_sum_program_(gpu::ShaderProgram::compute("methods/local_global/shaders/vertex_irradiance_sum.comp")),
        global_program_(gpu::ShaderProgram::compute("methods/local_global/shaders/global.comp")),
        local_program_(gpu::ShaderProgram::compute("methods/local_global/shaders/local.comp")),
        view_program_(gpu::ShaderProgram::graphics("methods/local_global/shaders/atlas_view.vert", "",
                                                   "methods/local_global/shaders/atlas_view.frag")),
        shade_program_(gpu::ShaderProgram::compute("methods/local_global/shaders/shade.comp", defines(scene))) {
    if (data_.atlas_size != texture_gbuffer_.size())
      throw Error(fmt::format("{}: local-global: precomputed for a {}-texel atlas, the atlas has {}", scene.source,
                              data_.atlas_size, texture_gbuffer_.size()));
    const int size = data_.atlas_size;
    illumination_ = gpu::make_image_texture(size, size, GL_RGBA32F, "local-global illumination map");
    local_ = gpu::make_image_texture(size, size, GL_RGBA32F, "local-global local response");
    texel_index_ = gpu::make_image_texture(size, size, GL_R32I, "local-global texel index");
    std::vector<std::int32_t> index(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), -1);
    for (std::size_t t = 0; t < data_.texel_xy.size(); ++t)
      index[(data_.texel_xy[t] >> 16) * static_cast<std::size_t>(size) + (data_.texel_xy[t] & 0xffffu)] = static_cast<std::int32_t>(t);
    glTextureSubImage2D(texel_index_, 0, 0, 0, size, size, GL_RED_INTEGER, GL_INT, index.data());
    memory_ += static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * (16 + 16 + 4);

    kernels_ = make_buffer(data_.kernels, "local-global kernels", memory_);
    const std::size_t vertices = data_.vertex_count();
    // Each vertex's texels in chunks of at most LUCENT_LG_VERTEX_CHUNK (llvmpipe's loop limit, local_global_io.h).
    std::vector<glm::uvec2> chunks;
    std::vector<std::uint32_t> vertex_chunks(vertices + 1, 0);
    for (std::size_t v = 0; v < vertices; ++v) {
      vertex_chunks[v] = static_cast<std::uint32_t>(chunks.size());
      const std::uint32_t end = data_.vertex_offsets[v + 1];
      for (std::uint32_t k = data_.vertex_offsets[v]; k < end; k += LUCENT_LG_VERTEX_CHUNK)
        chunks.emplace_back(k, std::min<std::uint32_t>(end, k + LUCENT_LG_VERTEX_CHUNK));
      if (chunks.size() - vertex_chunks[v] > LUCENT_LG_VERTEX_CHUNK)
        throw Error(fmt::format("{}: local-global: vertex {} has {} texels, more than {} chunks of {} can sum", scene.source,
                                v, end - data_.vertex_offsets[v], LUCENT_LG_VERTEX_CHUNK, LUCENT_LG_VERTEX_CHUNK));
    }
    vertex_chunks[vertices] = static_cast<std::uint32_t>(chunks.size());
    chunk_count_ = chunks.size();
    chunks_ = make_buffer(chunks, "local-global texel chunks", memory_);
    vertex_chunks_ = make_buffer(vertex_chunks, "local-global vertex chunks", memory_);
    chunk_sums_ = make_empty_buffer(chunk_count_ * 32, "local-global chunk sums", memory_);
    std::vector<glm::uvec4> vertex_texels;
    vertex_texels.reserve(data_.vertex_texels.size() * 2);
    for (const lg::VertexTexel& v : data_.vertex_texels) {
      vertex_texels.emplace_back(data_.texel_xy[v.texel], float_bits(v.dual), 0u, 0u);
      vertex_texels.emplace_back(float_bits(v.direct.x), float_bits(v.direct.y), float_bits(v.direct.z), 0u);
    }
    vertex_texels_ = make_buffer(vertex_texels, "local-global vertex texels", memory_);
    // global.comp runs one loop over a row: on llvmpipe a longer row would be cut short without an error.
    std::uint32_t longest_row = 0;
    for (std::size_t j = 0; j + 1 < data_.row_offsets.size(); ++j)
      longest_row = std::max(longest_row, data_.row_offsets[j + 1] - data_.row_offsets[j]);
    platform::check_loop_iterations(
        fmt::format("{}: /method/cutoff: local-global's longest row of the global matrix, {} form factors", scene.source,
                    longest_row),
        longest_row, "raise /method/cutoff or /method/vertex_spacing");
    row_offsets_ = make_buffer(data_.row_offsets, "local-global row offsets", memory_);
    form_factors_ = make_buffer(data_.form_factors, "local-global form factors", memory_);
    vertex_irradiance_ = make_empty_buffer(vertices * 32, "local-global vertex irradiance", memory_);
    vertex_radiosity_ = make_empty_buffer(vertices * 16, "local-global vertex radiosity", memory_);

    // Per corner of the scene's index buffer (translucent ranges): atlas coordinates and global vertex.
    std::vector<glm::uvec4> corners;
    std::size_t corner_base = 0;
    for (std::size_t k = 0; k < data_.objects.size(); ++k) {
      const std::uint32_t object = data_.objects[k].scene_object;
      const TriangleMesh& mesh = scene.objects[object].mesh;
      const auto range = std::find_if(scene_gpu.translucent_meshes().begin(), scene_gpu.translucent_meshes().end(),
                                      [&](const render::SceneGpu::MeshRange& r) { return r.object == object; });
      if (range == scene_gpu.translucent_meshes().end() || range->index_count != mesh.indices.size())
        throw Error(fmt::format("{}: local-global: object {} is not on the GPU as it was precomputed", scene.source, object));
      corners.resize(std::max<std::size_t>(corners.size(), range->first_index + range->index_count));
      for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
        const glm::vec2 uv = mesh.uvs[mesh.indices[c]];
        corners[range->first_index + c] = glm::uvec4(float_bits(uv.x), float_bits(uv.y), data_.corner_vertex[corner_base + c], 0u);
      }
      corner_base += mesh.indices.size();
    }
    corners_ = make_buffer(corners, "local-global corners", memory_);
    glCreateBuffers(1, &block_buffer_);
    glNamedBufferStorage(block_buffer_, sizeof(shader::LocalGlobalGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, block_buffer_, "local-global block");
    glCreateVertexArrays(1, &vao_);
    form_factor_count_ = data_.form_factors.size();
    texel_count_ = data_.texel_xy.size();
    vertex_count_ = vertices;
    cutoff_mm_ = data_.objects.empty() ? 0.0 : data_.objects.front().cutoff_radius * scene.scale_mm;
    // The tables live on the GPU now.
    data_ = lg::LocalGlobalData{};
  }

  ~LocalGlobal() override {
    GLuint textures[] = {illumination_, local_, texel_index_};
    glDeleteTextures(3, textures);
    GLuint buffers[] = {kernels_, chunks_, vertex_chunks_, chunk_sums_, vertex_texels_, row_offsets_, form_factors_,
                        vertex_irradiance_, vertex_radiosity_, corners_, block_buffer_};
    glDeleteBuffers(11, buffers);
    glDeleteVertexArrays(1, &vao_);
  }

  void prepare_frame(shader::FrameGPU& frame, bool restart) override {
    frames_ = restart ? 1 : frames_ + 1;
    light_gbuffer_.fill_frame(frame);
    frame.light_counts.w = kShadowTaps;
    frame.seeds.z = restart ? 1u : 0u;
    frame.shading = glm::vec4(params_.boolean("specular") ? 1.0f : 0.0f, params_.number("roughness"), 0.0f, 0.0f);
    const std::string show = params_.text("show");
    const int show_id = show == "local" ? LUCENT_LG_SHOW_LOCAL : show == "global" ? LUCENT_LG_SHOW_GLOBAL : LUCENT_LG_SHOW_COMBINED;
    block_ = shader::LocalGlobalGPU{glm::ivec4(texture_gbuffer_.size(), static_cast<int>(vertex_count_),
                                               static_cast<int>(texel_count_), 0),
                                    glm::ivec4(show_id, static_cast<int>(chunk_count_), 0, 0)};
    glNamedBufferSubData(block_buffer_, 0, sizeof(block_), &block_);
  }

  void render(const FrameContext& context) override {
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_METHOD, block_buffer_);
    // The radiosity depends on the lights, the meshes and the materials only: a frame in which only the camera
    // moved redraws the atlas view and shades.
    if (context.restart || !lit_) relight(context);
    lit_ = true;
    view_and_shade(context);
  }

 private:
  static constexpr int kShadowTaps = 3;

  void relight(const FrameContext& context) {
    const int size = texture_gbuffer_.size();
    const GLuint groups = static_cast<GLuint>((size + 7) / 8);
    const GLuint vertex_groups = static_cast<GLuint>((vertex_count_ + 63) / 64);
    light_gbuffer_.render(context.scene_gpu, context.profiler);
    if (!texture_drawn_) {  // rigid objects: the texture G-buffer never changes
      auto pass = context.profiler.pass("texture_gbuffer");
      texture_gbuffer_.render(context.scene_gpu);
      texture_drawn_ = true;
    }
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_METHOD, block_buffer_);
    {
      auto pass = context.profiler.pass("illumination");
      light_gbuffer_.bind_textures();
      texture_gbuffer_.bind_textures();
      glBindImageTexture(LUCENT_IMAGE_LG_ILLUMINATION, illumination_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
      glUseProgram(illumination_program_.id());
      glDispatchCompute(groups, groups, 1);
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    glBindTextureUnit(LUCENT_TEX_LG_ILLUMINATION, illumination_);
    glBindTextureUnit(LUCENT_TEX_LG_TEXEL_INDEX, texel_index_);
    {
      auto pass = context.profiler.pass("vertex_irradiance");
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_CHUNKS, chunks_);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_VERTEX_TEXELS, vertex_texels_);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_CHUNK_SUMS, chunk_sums_);
      glUseProgram(vertex_program_.id());
      const GLuint chunk_groups = static_cast<GLuint>((chunk_count_ + 63) / 64);
      if (chunk_groups > 0) glDispatchCompute(chunk_groups, 1, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_VERTEX_CHUNKS, vertex_chunks_);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_VERTEX_IRRADIANCE, vertex_irradiance_);
      glUseProgram(vertex_sum_program_.id());
      if (vertex_groups > 0) glDispatchCompute(vertex_groups, 1, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
      auto pass = context.profiler.pass("global");
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_ROW_OFFSETS, row_offsets_);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_FORM_FACTORS, form_factors_);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_VERTEX_RADIOSITY, vertex_radiosity_);
      glUseProgram(global_program_.id());
      if (vertex_groups > 0) glDispatchCompute(vertex_groups, 1, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
      auto pass = context.profiler.pass("local");
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_KERNELS, kernels_);
      glBindImageTexture(LUCENT_IMAGE_LG_LOCAL, local_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
      glUseProgram(local_program_.id());
      glDispatchCompute(groups, groups, 1);
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
  }

  void view_and_shade(const FrameContext& context) {
    const int width = context.camera_gbuffer.size_x(), height = context.camera_gbuffer.size_y();
    {
      auto pass = context.profiler.pass("atlas_view");
      view_.resize(width, height);  // atlas coordinates (target 0) and vertex radiosity (target 1)
      view_.begin_pass();
      glDisable(GL_CULL_FACE);
      glDisable(GL_BLEND);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_SCENE_VERTICES, context.scene_gpu.vertex_buffer());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_SCENE_INDICES, context.scene_gpu.index_buffer());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_CORNERS, corners_);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LG_VERTEX_RADIOSITY, vertex_radiosity_);
      glBindVertexArray(vao_);
      glUseProgram(view_program_.id());
      for (const render::SceneGpu::MeshRange& range : context.scene_gpu.translucent_meshes()) {
        block_.counts.w = static_cast<int>(range.first_index);
        glNamedBufferSubData(block_buffer_, 0, sizeof(block_), &block_);
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(range.index_count));
      }
      glBindVertexArray(0);
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    auto pass = context.profiler.pass("shade");
    light_gbuffer_.bind_textures();
    texture_gbuffer_.bind_textures();
    glBindTextureUnit(LUCENT_TEX_LG_TEXEL_INDEX, texel_index_);
    glBindTextureUnit(LUCENT_TEX_LG_LOCAL, local_);
    static_assert(LUCENT_TEX_LG_VIEW_RADIOSITY == LUCENT_TEX_LG_VIEW_ATLAS + 1);
    view_.bind_textures(LUCENT_TEX_LG_VIEW_ATLAS);
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUseProgram(shade_program_.id());
    glDispatchCompute(static_cast<GLuint>((width + 7) / 8), static_cast<GLuint>((height + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }

 public:
  int accumulated_frames() const override { return frames_; }
  void statistics(const FrameRecord& record, std::vector<FrameStatistic>& out) const override {
    (void)record;
    out.push_back({"texels", static_cast<double>(texel_count_), ""});
    out.push_back({"vertices", static_cast<double>(vertex_count_), ""});
    out.push_back({"form_factors", static_cast<double>(form_factor_count_), ""});
    out.push_back({"cutoff_radius", cutoff_mm_, "mm"});
  }
  // specular and roughness are read every frame.
  bool update_live_params(const Scene& scene) override {
    (void)scene;
    return true;
  }
  std::size_t gpu_memory_bytes() const override {
    const std::size_t atlas = static_cast<std::size_t>(texture_gbuffer_.size()) * static_cast<std::size_t>(texture_gbuffer_.size());
    return light_gbuffer_.gpu_memory_bytes() + atlas * 36 + memory_ + view_.gpu_memory_bytes();
  }

 private:
  const ParamValues& params_;
  lg::LocalGlobalData data_;
  render::LightGBuffer light_gbuffer_;
  texture_space::TextureGBuffer texture_gbuffer_;
  gpu::ShaderProgram illumination_program_, vertex_program_, vertex_sum_program_, global_program_, local_program_, view_program_, shade_program_;
  GLuint illumination_ = 0, local_ = 0, texel_index_ = 0;
  GLuint kernels_ = 0, chunks_ = 0, vertex_chunks_ = 0, chunk_sums_ = 0, vertex_texels_ = 0, row_offsets_ = 0, form_factors_ = 0;
  GLuint vertex_irradiance_ = 0, vertex_radiosity_ = 0, corners_ = 0, block_buffer_ = 0, vao_ = 0;
  gpu::ScreenTargets view_{2, "local-global atlas view"};
  std::size_t memory_ = 0;
  std::size_t form_factor_count_ = 0, texel_count_ = 0, vertex_count_ = 0, chunk_count_ = 0;
  double cutoff_mm_ = 0.0;
  shader::LocalGlobalGPU block_{};
  int frames_ = 0;
  bool lit_ = false, texture_drawn_ = false;
};

}  // namespace

std::unique_ptr<Method> create_local_global(const MethodSetup& setup) {
  if (!setup.atlas) throw Error("local-global: the renderer gave no texture atlas");
  lg::check_rigid(setup.scene);
  return std::make_unique<LocalGlobal>(setup.scene, setup.scene_gpu, *setup.atlas, setup.precomputed);
}

}  // namespace lucent::methods
