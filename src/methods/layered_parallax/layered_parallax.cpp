// layered_parallax.cpp: multi-layer parallax shading (Oat 2006, "Rendering Goopy Materials with Multiple Layers",
// as studied by Norberg 2010, Section 2.2): an outer layer (base colour, normal map, see-through weight) over an
// inner layer whose texture is shifted by depth parallax and lit by a blurred texture-space light map. Passes: the
// light G-buffer (shadows); every translucent object's diffuse irradiance drawn in texture space (one array layer
// per object) at reduced resolution; Poisson-disc blur passes over it; the camera pixels' texture coordinates and
// gradients; the shading (shaders/shade.comp). Everything is recomputed every frame, so deforming meshes work.
#include "methods/method.h"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "gpu/screen_targets.h"
#include "gpu/shader_program.h"
#include "lucent/error.h"
#include "media/tissue_maps.h"
#include "methods/layered_parallax/layered_parallax_io.h"
#include "render/light_gbuffer.h"
#include "render/view_accumulator.h"

namespace lucent::methods {
namespace {

ImageRGBA32F read_texture(const Scene& scene, const char* key) {
  std::filesystem::path path(scene.method_params.text(key));
  if (path.is_relative()) path = std::filesystem::path(scene.source).parent_path() / path;
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  try {
    if (ext == ".exr") return read_exr(path.string());
    if (ext != ".png") throw Error(fmt::format("{}: textures must be .png or .exr files", path.string()));
    const ImageRGBA8 bytes = read_png(path.string());
    ImageRGBA32F image;
    image.width = bytes.width, image.height = bytes.height;
    image.pixels.resize(bytes.pixels.size());
    for (std::size_t i = 0; i < bytes.pixels.size(); ++i) {
      const float v = static_cast<float>(bytes.pixels[i]) / 255.0f;
      // Colours are sRGB-encoded; alpha is linear.
      image.pixels[i] = i % 4 == 3 ? v : (v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f));
    }
    return image;
  } catch (const Error& e) {
    throw Error(fmt::format("{}: /method/{}: {}", scene.source, key, e.what()));
  }
}

// A PNG normal map stores 0.5 n + 0.5 per channel, linearly (no sRGB decoding).
ImageRGBA32F read_normal_map(const Scene& scene) {
  std::filesystem::path path(scene.method_params.text("outer_normal"));
  if (path.is_relative()) path = std::filesystem::path(scene.source).parent_path() / path;
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".png") return read_texture(scene, "outer_normal");
  try {
    const ImageRGBA8 bytes = read_png(path.string());
    ImageRGBA32F image;
    image.width = bytes.width, image.height = bytes.height;
    image.pixels.resize(bytes.pixels.size());
    for (std::size_t i = 0; i < bytes.pixels.size(); ++i)
      image.pixels[i] = i % 4 == 3 ? 1.0f : 2.0f * static_cast<float>(bytes.pixels[i]) / 255.0f - 1.0f;
    return image;
  } catch (const Error& e) {
    throw Error(fmt::format("{}: /method/outer_normal: {}", scene.source, e.what()));
  }
}

GLuint upload_texture(const ImageRGBA32F& image, const char* label, bool mipmaps) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  int levels = 1;
  if (mipmaps)
    for (int s = std::max(image.width, image.height); s > 1; s /= 2) ++levels;
  glTextureStorage2D(texture, levels, GL_RGBA32F, image.width, image.height);
  // The file's top row first; texture coordinate v = 0 at the bottom row.
  std::vector<float> rows(image.pixels.size());
  const std::size_t row = static_cast<std::size_t>(image.width) * 4;
  for (int y = 0; y < image.height; ++y)
    std::copy_n(image.pixels.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(image.height - 1 - y)), row,
                rows.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y)));
  glTextureSubImage2D(texture, 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rows.data());
  if (mipmaps) glGenerateTextureMipmap(texture);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_REPEAT);
  gpu::label_object(GL_TEXTURE, texture, label);
  return texture;
}

class LayeredParallax final : public Method {
 public:
  LayeredParallax(const Scene& scene, const render::SceneGpu& scene_gpu)
      : params_(scene.method_params),
        scale_mm_(scene.scale_mm),
        light_gbuffer_(scene, scene_gpu, params_.integer("light_map_size")),
        light_map_program_(gpu::ShaderProgram::graphics("methods/layered_parallax/shaders/light_map.vert", "",
                                                        "methods/layered_parallax/shaders/light_map.frag",
                                                        render::light_sampling_defines(scene))),
        blur_program_(gpu::ShaderProgram::compute("methods/layered_parallax/shaders/blur.comp")),
        surface_program_(gpu::ShaderProgram::graphics("methods/layered_parallax/shaders/surface.vert", "",
                                                      "methods/layered_parallax/shaders/surface.frag")),
        shade_program_(gpu::ShaderProgram::compute("methods/layered_parallax/shaders/shade.comp",
                                                   render::light_sampling_defines(scene))) {
    for (const SceneObject& o : scene.objects)
      if (o.material && o.blob_resolution > 0)
        throw Error(fmt::format("{}: method layered-parallax needs texture coordinates; blob surface '{}' has none",
                                scene.source, o.name));
    const bool procedural = params_.text("outer_base").empty() || params_.text("outer_normal").empty() ||
                            params_.text("inner_base").empty();
    media::TissueSurfaceTextures tissue;
    if (procedural) tissue = media::tissue_surface_textures(params_.integer("texture_size"));
    const ImageRGBA32F outer = params_.text("outer_base").empty() ? tissue.outer_base : read_texture(scene, "outer_base");
    const ImageRGBA32F normal = params_.text("outer_normal").empty() ? tissue.outer_normal : read_normal_map(scene);
    const ImageRGBA32F inner = params_.text("inner_base").empty() ? tissue.inner_base : read_texture(scene, "inner_base");
    outer_base_ = upload_texture(outer, "layered-parallax outer base", false);
    outer_normal_ = upload_texture(normal, "layered-parallax outer normal", false);
    inner_base_ = upload_texture(inner, "layered-parallax inner base", true);
    texture_bytes_ = (outer.pixels.size() + normal.pixels.size() + inner.pixels.size() * 4 / 3) * sizeof(float);

    map_size_ = params_.integer("irradiance_map_size");
    map_layers_ = static_cast<int>(std::max<std::size_t>(scene.objects.size(), 1));
    GLint max_layers = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    if (map_layers_ > max_layers)
      throw Error(fmt::format("{}: method layered-parallax keeps one light-map layer per object; {} objects exceed "
                              "the driver's {} array layers",
                              scene.source, map_layers_, max_layers));
    for (GLuint& map : light_maps_) {
      glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &map);
      glTextureStorage3D(map, 1, GL_RGBA32F, map_size_, map_size_, map_layers_);
      glTextureParameteri(map, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(map, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(map, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTextureParameteri(map, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      gpu::label_object(GL_TEXTURE, map, "layered-parallax light map");
    }
    glCreateFramebuffers(1, &map_framebuffer_);
    glNamedFramebufferTexture(map_framebuffer_, GL_COLOR_ATTACHMENT0, light_maps_[0], 0);
    glNamedFramebufferDrawBuffer(map_framebuffer_, GL_COLOR_ATTACHMENT0);
    if (glCheckNamedFramebufferStatus(map_framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw Error(fmt::format("layered-parallax: the {}x{}x{} light-map framebuffer is incomplete", map_size_, map_size_,
                              map_layers_));
    glCreateBuffers(1, &block_buffer_);
    glNamedBufferStorage(block_buffer_, sizeof(shader::LayeredParallaxGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, block_buffer_, "layered-parallax block");
  }
  ~LayeredParallax() override {
    glDeleteBuffers(1, &block_buffer_);
    GLuint textures[] = {outer_base_, outer_normal_, inner_base_, light_maps_[0], light_maps_[1]};
    glDeleteTextures(5, textures);
    glDeleteFramebuffers(1, &map_framebuffer_);
  }

  void prepare_frame(shader::FrameGPU& frame, bool restart) override {
    restart = accumulated_.begin_frame(frame, restart || !params_.boolean("progressive"));
    light_gbuffer_.fill_frame(frame);
    frame.seeds.z = restart ? 1u : 0u;
    frame.shading = glm::vec4(params_.boolean("specular") ? 1.0f : 0.0f, params_.number("roughness"), 0.0f, 0.0f);
    const float depth_mm = static_cast<float>(params_.number("inner_depth"));
    block_.layers = glm::vec4(depth_mm / scale_mm_, static_cast<float>(params_.number("tiling")),
                              static_cast<float>(params_.number("light_blur")) * depth_mm,
                              static_cast<float>(params_.number("inner_blur")) * scale_mm_);
    block_.counts = glm::ivec4(map_size_, map_layers_, 0, 0);
  }

  void render(const FrameContext& context) override {
    light_gbuffer_.render(context.scene_gpu, context.profiler);
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_METHOD, block_buffer_);
    glNamedBufferSubData(block_buffer_, 0, sizeof(block_), &block_);
    light_gbuffer_.bind_textures();
    {
      auto pass = context.profiler.pass("light_map");
      glBindFramebuffer(GL_FRAMEBUFFER, map_framebuffer_);
      glViewport(0, 0, map_size_, map_size_);
      const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      glClearNamedFramebufferfv(map_framebuffer_, GL_COLOR, 0, zero);
      glDisable(GL_DEPTH_TEST);
      glDisable(GL_CULL_FACE);
      glUseProgram(light_map_program_.id());
      context.scene_gpu.draw_translucent();
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    int current = 0;
    const int passes = params_.integer("blur_passes");
    {
      auto pass = context.profiler.pass("blur");
      glUseProgram(blur_program_.id());
      for (int p = 0; p < passes; ++p) {
        shader::LayeredParallaxGPU block = block_;
        block.counts.z = p;
        glNamedBufferSubData(block_buffer_, 0, sizeof(block), &block);
        glBindTextureUnit(LUCENT_TEX_LPAR_LIGHT_MAP, light_maps_[current]);
        glBindImageTexture(LUCENT_IMAGE_LPAR_BLURRED, light_maps_[1 - current], 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glDispatchCompute(static_cast<GLuint>((map_size_ + 7) / 8), static_cast<GLuint>((map_size_ + 7) / 8),
                          static_cast<GLuint>(map_layers_));
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        current = 1 - current;
      }
      blurred_texels_ = static_cast<double>(passes) * map_size_ * map_size_ * map_layers_;
    }
    {
      auto pass = context.profiler.pass("surface");
      surface_.resize(accumulated_.width(), accumulated_.height());
      surface_.begin_pass();
      glUseProgram(surface_program_.id());
      context.scene_gpu.draw_all();
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    auto pass = context.profiler.pass("shade");
    glNamedBufferSubData(block_buffer_, 0, sizeof(block_), &block_);
    glBindTextureUnit(LUCENT_TEX_LPAR_OUTER_BASE, outer_base_);
    glBindTextureUnit(LUCENT_TEX_LPAR_OUTER_NORMAL, outer_normal_);
    glBindTextureUnit(LUCENT_TEX_LPAR_INNER_BASE, inner_base_);
    glBindTextureUnit(LUCENT_TEX_LPAR_LIGHT_MAP, light_maps_[current]);
    surface_.bind_textures(LUCENT_TEX_LPAR_SURFACE);
    accumulated_.bind(LUCENT_IMAGE_LPAR_SUM);
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUseProgram(shade_program_.id());
    glDispatchCompute(static_cast<GLuint>((accumulated_.width() + 7) / 8), static_cast<GLuint>((accumulated_.height() + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }

  int accumulated_frames() const override { return accumulated_.frames(); }
  void statistics(const FrameRecord& record, std::vector<FrameStatistic>& out) const override {
    out.push_back({"light_map_texels", record.ran("blur") ? blurred_texels_ : 0.0, ""});
  }
  bool update_live_params(const Scene& scene) override {
    (void)scene;
    return true;
  }
  bool update_materials(const Scene& scene) override {
    (void)scene;
    return true;  // the shading reads no material coefficient
  }
  std::size_t gpu_memory_bytes() const override {
    return light_gbuffer_.gpu_memory_bytes() + accumulated_.gpu_memory_bytes() + texture_bytes_ +
           2 * static_cast<std::size_t>(map_size_) * static_cast<std::size_t>(map_size_) *
               static_cast<std::size_t>(map_layers_) * 16 +
           surface_.gpu_memory_bytes();
  }

 private:
  const ParamValues& params_;
  float scale_mm_;
  render::LightGBuffer light_gbuffer_;
  gpu::ShaderProgram light_map_program_, blur_program_, surface_program_, shade_program_;
  render::ViewAccumulator accumulated_{"layered-parallax accumulated radiance"};
  shader::LayeredParallaxGPU block_{};
  GLuint block_buffer_ = 0, outer_base_ = 0, outer_normal_ = 0, inner_base_ = 0;
  GLuint light_maps_[2] = {0, 0};
  GLuint map_framebuffer_ = 0;
  gpu::ScreenTargets surface_{3, "layered-parallax surface"};
  int map_size_ = 0, map_layers_ = 0;
  std::size_t texture_bytes_ = 0;
  double blurred_texels_ = 0.0;
};

}  // namespace

std::unique_ptr<Method> create_layered_parallax(const MethodSetup& setup) {
  return std::make_unique<LayeredParallax>(setup.scene, setup.scene_gpu);
}

}  // namespace lucent::methods
