// layered_stm.cpp: subsurface texture mapping (Francois et al. 2006), as studied by Norberg 2010, Section 2.1: single
// scattering in a stack of up to four layers whose thicknesses vary over the surface (heightfields packed in the
// channels of one RGBA texture), ray-marched per camera pixel along the refracted view ray. Passes: the light
// G-buffer (shadows); a least-squares plane per vertex from its neighbours' current positions (refitted every
// frame, so deforming meshes keep valid planes); the camera pixels' texture coordinates, their gradients and the
// interpolated plane; the march (shaders/march.comp, the physics shared with C++ in media/layer_stack.h).
#include "methods/method.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unordered_map>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "gpu/screen_targets.h"
#include "gpu/shader_program.h"
#include "lucent/error.h"
#include "media/layer_stack.h"
#include "media/tissue_maps.h"
#include "methods/layered_stm/layered_stm_io.h"
#include "render/light_gbuffer.h"
#include "render/view_accumulator.h"

namespace lucent::methods {
namespace {

// The per-layer coefficients of the method's parameters, checked; in mm^-1. Empty: one layer of each material.
struct LayerCoefficients {
  std::vector<glm::vec3> sigma_s, sigma_t, g;
};

LayerCoefficients read_layers(const Scene& scene) {
  const ParamValues& p = scene.method_params;
  LayerCoefficients c{p.vec3_list("sigma_s"), p.vec3_list("sigma_t"), p.vec3_list("g")};
  const std::string& where = scene.source;
  if (c.sigma_s.size() > static_cast<std::size_t>(shader::kMaxStackLayers))
    throw Error(fmt::format("{}: /method/sigma_s: {} layers; at most {} (one RGBA map)", where, c.sigma_s.size(),
                            shader::kMaxStackLayers));
  if (c.sigma_t.size() != c.sigma_s.size())
    throw Error(fmt::format("{}: /method/sigma_t: {} layers, but sigma_s has {}; give both for every layer", where,
                            c.sigma_t.size(), c.sigma_s.size()));
  if (!c.g.empty() && c.g.size() != c.sigma_s.size())
    throw Error(fmt::format("{}: /method/g: {} layers, but sigma_s has {}; give g for every layer or none", where,
                            c.g.size(), c.sigma_s.size()));
  for (std::size_t i = 0; i < c.sigma_s.size(); ++i)
    for (int b = 0; b < 3; ++b)
      if (c.sigma_t[i][b] < c.sigma_s[i][b])
        throw Error(fmt::format("{}: /method/sigma_t/{}: layer {}: sigma_t[{}] = {} mm^-1 is below sigma_s[{}] = {} "
                                "mm^-1; extinction includes scattering (sigma_t = sigma_a + sigma_s)",
                                where, i, i, b, c.sigma_t[i][b], b, c.sigma_s[i][b]));
  if (c.g.empty()) c.g.assign(c.sigma_s.size(), glm::vec3(0.0f));
  return c;
}

// The smallest extinction of the stack [mm^-1] (of the translucent materials when the stack uses them).
float smallest_extinction(const Scene& scene, const LayerCoefficients& layers) {
  float smallest = 1e30f;
  for (const glm::vec3& t : layers.sigma_t) smallest = std::min({smallest, t.x, t.y, t.z});
  if (layers.sigma_t.empty())
    for (const SceneObject& o : scene.objects)
      if (o.material) {
        const glm::vec3 t = o.material->sigma_t();
        smallest = std::min({smallest, t.x, t.y, t.z});
      }
  return smallest;
}

ImageRGBA32F layer_maps(const Scene& scene, std::size_t layer_count) {
  const std::string& maps = scene.method_params.text("maps");
  if (maps == "tissue") return media::tissue_layer_maps(scene.method_params.integer("map_size"));
  if (maps == "uniform") {
    const float t = 1.0f / static_cast<float>(std::max<std::size_t>(layer_count, 1));
    return media::uniform_layer_maps(t, t, t, t);
  }
  std::filesystem::path path(maps);
  if (path.is_relative()) path = std::filesystem::path(scene.source).parent_path() / path;
  try {
    return media::read_layer_maps(path.string());
  } catch (const Error& e) {
    throw Error(fmt::format("{}: /method/maps: {}", scene.source, e.what()));
  }
}

class LayeredStm final : public Method {
 public:
  LayeredStm(const Scene& scene, const render::SceneGpu& scene_gpu)
      : params_(scene.method_params),
        layers_(read_layers(scene)),
        scale_mm_(scene.scale_mm),
        light_gbuffer_(scene, scene_gpu, params_.integer("light_map_size")),
        plane_program_(gpu::ShaderProgram::compute("methods/layered_stm/shaders/planes.comp")),
        surface_program_(gpu::ShaderProgram::graphics("methods/layered_stm/shaders/surface.vert", "",
                                                      "methods/layered_stm/shaders/surface.frag")),
        march_program_(gpu::ShaderProgram::compute("methods/layered_stm/shaders/march.comp",
                                                   render::light_sampling_defines(scene))) {
    for (const SceneObject& o : scene.objects)
      if (o.material && o.blob_resolution > 0)
        throw Error(fmt::format("{}: method layered-stm needs texture coordinates; blob surface '{}' has none",
                                scene.source, o.name));
    glCreateBuffers(1, &block_buffer_);
    glNamedBufferStorage(block_buffer_, sizeof(shader::LayeredStmGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, block_buffer_, "layered-stm block");
    upload_maps(layer_maps(scene, layers_.sigma_s.size()));
    build_neighbours(scene, scene_gpu);
  }
  ~LayeredStm() override {
    GLuint buffers[] = {block_buffer_, fit_buffer_, neighbour_buffer_, plane_buffer_};
    glDeleteBuffers(4, buffers);
    glDeleteTextures(1, &maps_);
  }

  void prepare_frame(shader::FrameGPU& frame, bool restart) override {
    restart = accumulated_.begin_frame(frame, restart || !params_.boolean("progressive"));
    light_gbuffer_.fill_frame(frame);
    frame.seeds.z = restart ? 1u : 0u;
    frame.shading = glm::vec4(params_.boolean("specular") ? 1.0f : 0.0f, params_.number("roughness"), 0.0f, 0.0f);
    shader::LayeredStmGPU block{};
    block.counts = glm::ivec4(params_.integer("samples"), static_cast<int>(layers_.sigma_s.size()),
                              params_.boolean("jitter") ? 1 : 0, fitted_vertices_);
    const float to_scene = scale_mm_;  // [1/mm] -> [1/scene unit]
    block.stack = glm::vec4(static_cast<float>(params_.number("depth")) / scale_mm_,
                            static_cast<float>(params_.number("tiling")), 0.0f, 0.0f);
    for (std::size_t i = 0; i < layers_.sigma_s.size(); ++i) {
      block.sigma_s[i] = glm::vec4(layers_.sigma_s[i] * to_scene, 0.0f);
      block.sigma_t[i] = glm::vec4(layers_.sigma_t[i] * to_scene, 0.0f);
      const glm::vec3 g = layers_.g[i];
      block.k[i] = glm::vec4(shader::schlick_k_from_g(g.x), shader::schlick_k_from_g(g.y),
                             shader::schlick_k_from_g(g.z), 0.0f);
    }
    glNamedBufferSubData(block_buffer_, 0, sizeof(block), &block);
  }

  void render(const FrameContext& context) override {
    light_gbuffer_.render(context.scene_gpu, context.profiler);
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_METHOD, block_buffer_);
    {
      auto pass = context.profiler.pass("planes");
      if (fitted_vertices_ > 0) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LSTM_VERTICES, context.scene_gpu.vertex_buffer());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LSTM_FIT, fit_buffer_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LSTM_NEIGHBOURS, neighbour_buffer_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LSTM_PLANES, plane_buffer_);
        glUseProgram(plane_program_.id());
        glDispatchCompute(static_cast<GLuint>((fitted_vertices_ + 63) / 64), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
      }
    }
    {
      auto pass = context.profiler.pass("surface");
      surface_.resize(accumulated_.width(), accumulated_.height());
      surface_.begin_pass();
      glDisable(GL_CULL_FACE);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_LSTM_PLANES, plane_buffer_);
      glUseProgram(surface_program_.id());
      context.scene_gpu.draw_all();
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    auto pass = context.profiler.pass("march");
    light_gbuffer_.bind_textures();
    glBindTextureUnit(LUCENT_TEX_LSTM_MAPS, maps_);
    surface_.bind_textures(LUCENT_TEX_LSTM_SURFACE);
    accumulated_.bind(LUCENT_IMAGE_LSTM_SUM);
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUseProgram(march_program_.id());
    glDispatchCompute(static_cast<GLuint>((accumulated_.width() + 7) / 8), static_cast<GLuint>((accumulated_.height() + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }

  int accumulated_frames() const override { return accumulated_.frames(); }
  void statistics(const FrameRecord& record, std::vector<FrameStatistic>& out) const override {
    const double samples = static_cast<double>(record.counters.translucent_pixels) * params_.integer("samples");
    const double ms = record.pass_ms("march");
    out.push_back({"march_samples", samples, ""});
    out.push_back({"march_samples_per_second", ms > 0.0 ? samples / (ms * 1e-3) : 0.0, "1/s"});
  }
  // samples, jitter, depth, tiling, specular and roughness are read every frame; the layers' coefficients are
  // checked at creation, so edits of those rebuild.
  bool update_live_params(const Scene& scene) override {
    (void)scene;
    return true;
  }
  bool update_materials(const Scene& scene) override {
    (void)scene;
    // The shaders read eta (and a stack of the objects' own materials) from the material buffer each frame; only
    // the automatic fit radius of such a stack was derived from the materials on the CPU.
    return !layers_.sigma_s.empty() || params_.number("fit_radius") > 0.0;
  }
  std::size_t gpu_memory_bytes() const override {
    return light_gbuffer_.gpu_memory_bytes() + accumulated_.gpu_memory_bytes() + maps_bytes_ + neighbour_bytes_ +
           surface_.gpu_memory_bytes();
  }

 private:
  void upload_maps(const ImageRGBA32F& image) {
    glCreateTextures(GL_TEXTURE_2D, 1, &maps_);
    glTextureStorage2D(maps_, 1, GL_RGBA32F, image.width, image.height);
    // The file's top row first; texture coordinate v = 0 at the bottom row.
    std::vector<float> rows(image.pixels.size());
    const std::size_t row = static_cast<std::size_t>(image.width) * 4;
    for (int y = 0; y < image.height; ++y)
      std::copy_n(image.pixels.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(image.height - 1 - y)), row,
                  rows.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y)));
    glTextureSubImage2D(maps_, 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rows.data());
    glTextureParameteri(maps_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(maps_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(maps_, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(maps_, GL_TEXTURE_WRAP_T, GL_REPEAT);
    gpu::label_object(GL_TEXTURE, maps_, "layered-stm layer maps");
    maps_bytes_ = image.pixels.size() * sizeof(float);
  }

  // Neighbour lists for the plane fit, from the undeformed vertices as uploaded: for every vertex of a translucent
  // mesh, the vertices of the same mesh within the fit radius whose normals face the same side (itself included;
  // so that the far side of a thin part does not pull the plane inside), evenly thinned to max_neighbours.
  void build_neighbours(const Scene& scene, const render::SceneGpu& scene_gpu) {
    GLint64 vertex_bytes = 0;
    glGetNamedBufferParameteri64v(scene_gpu.vertex_buffer(), GL_BUFFER_SIZE, &vertex_bytes);
    const std::size_t vertex_count = static_cast<std::size_t>(vertex_bytes) / sizeof(shader::VertexGPU);
    glCreateBuffers(1, &plane_buffer_);
    std::vector<shader::LstmPlaneGPU> zero_planes(std::max<std::size_t>(vertex_count, 1));
    glNamedBufferStorage(plane_buffer_, static_cast<GLsizeiptr>(zero_planes.size() * sizeof(shader::LstmPlaneGPU)),
                         zero_planes.data(), 0);
    gpu::label_object(GL_BUFFER, plane_buffer_, "layered-stm planes");
    std::vector<shader::VertexGPU> vertices(vertex_count);
    if (vertex_count > 0)
      glGetNamedBufferSubData(scene_gpu.vertex_buffer(), 0, static_cast<GLsizeiptr>(vertex_count * sizeof(shader::VertexGPU)),
                              vertices.data());
    const float radius_mm = params_.number("fit_radius") > 0.0
                                ? static_cast<float>(params_.number("fit_radius"))
                                : 3.0f / std::max(smallest_extinction(scene, layers_), 1e-6f);
    const float radius = radius_mm / scene.scale_mm;
    const std::size_t max_neighbours = static_cast<std::size_t>(params_.integer("max_neighbours"));
    std::vector<glm::uvec2> fit;
    std::vector<std::uint32_t> neighbours;
    for (const render::SceneGpu::MeshRange& range : scene_gpu.translucent_meshes()) {
      std::vector<std::uint32_t> indices(range.index_count);
      glGetNamedBufferSubData(scene_gpu.index_buffer(), static_cast<GLintptr>(range.first_index * sizeof(std::uint32_t)),
                              static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data());
      std::sort(indices.begin(), indices.end());
      indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
      // Mesh bounds cap the radius: a plane wider than the mesh is the mesh's own best plane.
      glm::vec3 lower(1e30f), upper(-1e30f);
      for (std::uint32_t v : indices) {
        lower = glm::min(lower, glm::vec3(vertices[v].position));
        upper = glm::max(upper, glm::vec3(vertices[v].position));
      }
      const float r = std::min(radius, std::max(glm::length(upper - lower), 1e-6f));
      auto cell_of = [&](const glm::vec3& p) { return glm::ivec3(glm::floor((p - lower) / r)); };
      auto key = [](glm::ivec3 c) {
        return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.x) & 0x1FFFFF) << 42) |
               (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.y) & 0x1FFFFF) << 21) |
               static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.z) & 0x1FFFFF);
      };
      std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
      for (std::uint32_t v : indices) grid[key(cell_of(glm::vec3(vertices[v].position)))].push_back(v);
      std::vector<std::uint32_t> found;
      for (std::uint32_t v : indices) {
        const glm::vec3 p(vertices[v].position);
        const glm::ivec3 c = cell_of(p);
        found.clear();
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              auto it = grid.find(key(c + glm::ivec3(dx, dy, dz)));
              if (it == grid.end()) continue;
              for (std::uint32_t w : it->second)
                if (glm::length(glm::vec3(vertices[w].position) - p) <= r &&
                    glm::dot(glm::vec3(vertices[w].normal), glm::vec3(vertices[v].normal)) > 0.0f)
                  found.push_back(w);
            }
        fit.push_back(glm::uvec2(v, static_cast<std::uint32_t>(neighbours.size())));
        const std::size_t n = found.size(), keep = std::min(n, max_neighbours);
        for (std::size_t i = 0; i < keep; ++i) neighbours.push_back(found[i * n / keep]);
      }
    }
    fitted_vertices_ = static_cast<int>(fit.size());
    fit.push_back(glm::uvec2(0, static_cast<std::uint32_t>(neighbours.size())));
    if (neighbours.empty()) neighbours.push_back(0);
    glCreateBuffers(1, &fit_buffer_);
    glNamedBufferStorage(fit_buffer_, static_cast<GLsizeiptr>(fit.size() * sizeof(glm::uvec2)), fit.data(), 0);
    glCreateBuffers(1, &neighbour_buffer_);
    glNamedBufferStorage(neighbour_buffer_, static_cast<GLsizeiptr>(neighbours.size() * sizeof(std::uint32_t)),
                         neighbours.data(), 0);
    gpu::label_object(GL_BUFFER, fit_buffer_, "layered-stm fitted vertices");
    gpu::label_object(GL_BUFFER, neighbour_buffer_, "layered-stm neighbours");
    neighbour_bytes_ = fit.size() * sizeof(glm::uvec2) + neighbours.size() * sizeof(std::uint32_t) +
                       zero_planes.size() * sizeof(shader::LstmPlaneGPU);
  }

  const ParamValues& params_;
  LayerCoefficients layers_;
  float scale_mm_;
  render::LightGBuffer light_gbuffer_;
  gpu::ShaderProgram plane_program_, surface_program_, march_program_;
  render::ViewAccumulator accumulated_{"layered-stm accumulated radiance"};
  GLuint block_buffer_ = 0, fit_buffer_ = 0, neighbour_buffer_ = 0, plane_buffer_ = 0;
  GLuint maps_ = 0;
  gpu::ScreenTargets surface_{5, "layered-stm surface"};
  int fitted_vertices_ = 0;
  std::size_t maps_bytes_ = 0, neighbour_bytes_ = 0;
};

}  // namespace

std::unique_ptr<Method> create_layered_stm(const MethodSetup& setup) {
  return std::make_unique<LayeredStm>(setup.scene, setup.scene_gpu);
}

}  // namespace lucent::methods
