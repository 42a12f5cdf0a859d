// voxel_paths.cpp: the "voxel-paths" method: subsurface scattering as the shortest optical path through a solid
// voxelization of the translucent objects (after "Real-time rendering of heterogeneous translucent materials
// using Dijkstra's algorithm", shared/papers/voxel-dijkstra-heterogeneous-sss.txt). Per frame: the light
// G-buffer (the paper's reflective shadow map), GPU voxelization (voxelizer.h), lit voxels initialized to
// -ln(F_t P) (eqs. 2-3), shortest optical paths by parallel relaxation (relaxation_solver.h; verified against
// the CPU Dijkstra of voxel_dijkstra.h), exp(-n) into a 3D texture and surface shading F_t exp(-n) / pi (eq. 1).
// Limits: point and spot lights scatter only from the outside of the objects (a light inside one sees back faces);
// deforming objects are voxelized undeformed; blob surfaces are refused. See docs/methods/voxel-paths.md.
#include "methods/method.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "gpu/shader_program.h"
#include "lucent/error.h"
#include "methods/voxel_paths/coefficient_field.h"
#include "methods/voxel_paths/relaxation_solver.h"
#include "methods/voxel_paths/voxelizer.h"
#include "render/light_gbuffer.h"

namespace lucent::methods {
namespace {

using namespace voxel_paths;

constexpr int kPaddingVoxels = 2;  // outside voxels around the objects: surface voxels keep outside neighbours

TranslucentTriangles checked_triangles(const Scene& scene, bool effective_transport) {
  for (const SceneObject& object : scene.objects)
    if (object.translucent() && object.blob_resolution > 0)
      throw Error(fmt::format("{}: method voxel-paths does not voxelize blob surfaces yet (object '{}')",
                              scene.source, object.name));
  return gather_translucent_triangles(scene, effective_transport);
}

class VoxelPaths final : public Method {
 public:
  VoxelPaths(const Scene& scene, const render::SceneGpu& scene_gpu)
      : params_(scene.method_params),
        light_gbuffer_(scene, scene_gpu, params_.integer("light_map_size")),
        triangles_(checked_triangles(scene, params_.text("extinction") == "sigma_tr")),
        grid_(grid_around(scene_gpu.translucent_lower(), scene_gpu.translucent_upper(), params_.integer("resolution"),
                          kPaddingVoxels)),
        source_{scene_gpu.vertex_buffer(), scene_gpu.index_buffer(), {}},
        solver_(params_.text("solver") == "sweep" ? RelaxationSchedule::kSweep : RelaxationSchedule::kActiveBlocks),
        flux_program_(gpu::ShaderProgram::compute("methods/voxel_paths/shaders/initialize_flux.comp", shader_defines())),
        distances_program_(gpu::ShaderProgram::compute("methods/voxel_paths/shaders/initialize_distances.comp", shader_defines())),
        radiance_program_(gpu::ShaderProgram::compute("methods/voxel_paths/shaders/radiance.comp", shader_defines())),
        shade_program_(gpu::ShaderProgram::compute("methods/voxel_paths/shaders/shade.comp",
                                                   render::light_sampling_defines(scene) + shader_defines())) {
    for (const render::SceneGpu::MeshRange& mesh : scene_gpu.translucent_meshes())
      source_.objects.push_back({mesh.first_index, mesh.index_count, mesh.object + 1});
    const GLsizei r = grid_.resolution;
    glCreateBuffers(1, &flux_);
    glNamedBufferData(flux_, static_cast<GLsizeiptr>(grid_.voxel_count() * 12), nullptr, GL_DYNAMIC_DRAW);
    gpu::label_object(GL_BUFFER, flux_, "voxel-paths entering flux");
    glCreateTextures(GL_TEXTURE_3D, 1, &radiance_);
    glTextureStorage3D(radiance_, 1, GL_RGBA16F, r, r, r);
    glTextureParameteri(radiance_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(radiance_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
      glTextureParameteri(radiance_, wrap, GL_CLAMP_TO_EDGE);
    gpu::label_object(GL_TEXTURE, radiance_, "voxel-paths radiance");
    solver_.resize(grid_);
    // Fixed-point flux unit: the brightest texel of any light adds 2^16 units (directional: E A_texel; point and
    // spot: I (2 tan(a) / S)^2, the on-axis texel's power; cos^3 and the spot cone only lower it).
    float brightest = 0.0f;
    const render::LightViews& views = light_gbuffer_.views();
    const auto size = static_cast<float>(light_gbuffer_.size());
    for (const shader::LightGPU& light : views.lights) {
      const shader::ViewGPU& view = views.views[static_cast<std::size_t>(light.views.x)];
      float texel_power = 0.0f;  // per unit of power.rgb
      if (static_cast<int>(light.position.w) == LUCENT_LIGHT_DIRECTIONAL) {
        float texel = view.direction.w / size;
        texel_power = texel * texel;
      } else {
        float plane_texel = 2.0f * std::tan(0.5f * view.radiance.w * size) / size;
        texel_power = plane_texel * plane_texel;
      }
      brightest = std::max(brightest, std::max({light.power.r, light.power.g, light.power.b}) * texel_power);
    }
    flux_unit_ = brightest > 0.0f ? brightest / 65536.0f : 1.0f;
  }
  ~VoxelPaths() override {
    glDeleteBuffers(1, &flux_);
    glDeleteTextures(1, &radiance_);
  }

  void prepare_frame(shader::FrameGPU& frame, bool restart) override {
    // The radiance volume depends on geometry, lights, materials and time, not on the camera: it is solved
    // again only when something else changed (restart: a new time of an animated scene; other edits rebuild the
    // method), so camera moves cost the shading pass alone.
    solve_needed_ = solve_needed_ || restart;
    light_gbuffer_.fill_frame(frame);
    frame.light_counts.w = 3;  // shadow taps of the direct shading
    frame.shading = glm::vec4(params_.boolean("specular") ? 1.0f : 0.0f, params_.number("roughness"), 0.0f, 0.0f);
    width_ = frame.output_size.x, height_ = frame.output_size.y;
  }

  void render(const FrameContext& context) override {
    if (!solve_needed_) {
      auto pass = context.profiler.pass("voxel_shade");
      shade(context);
      return;
    }
    light_gbuffer_.render(context.scene_gpu, context.profiler);
    {
      auto pass = context.profiler.pass("voxelize");
      voxelizer_.voxelize(source_, grid_);
    }
    {
      auto pass = context.profiler.pass("voxel_field");
      field_.fill(grid_, voxelizer_.labels_buffer(), triangles_);
    }
    {
      auto pass = context.profiler.pass("voxel_initialize");
      initialize();
    }
    {
      auto pass = context.profiler.pass("relax");
      stats_ = solver_.solve(grid_, voxelizer_.labels_buffer(), field_.buffer(),
                             params_.integer("check_every"), params_.integer("max_iterations"));
    }
    {
      auto pass = context.profiler.pass("voxel_shade");
      radiance();
      shade(context);
    }
    solve_needed_ = false;  // only after a complete solve: a throw above leaves the next frame to solve again
  }

  int accumulated_frames() const override { return 1; }
  void statistics(const FrameRecord& record, std::vector<FrameStatistic>& out) const override {
    out.push_back({"voxels", static_cast<double>(grid_.voxel_count()), ""});
    out.push_back({"solved", record.ran("relax") ? 1.0 : 0.0, ""});
    out.push_back({"relaxation_sweeps", static_cast<double>(stats_.iterations), ""});
  }
  std::size_t gpu_memory_bytes() const override {
    return light_gbuffer_.gpu_memory_bytes() + voxelizer_.gpu_memory_bytes() + field_.gpu_memory_bytes() +
           grid_.voxel_count() * (16 + 12 + 8);
  }

 private:
  void set_grid_uniforms(GLuint program) const {
    glUniform3fv(glGetUniformLocation(program, "u_origin"), 1, &grid_.origin.x);
    glUniform1f(glGetUniformLocation(program, "u_voxel_size"), grid_.voxel_size);
    glUniform1i(glGetUniformLocation(program, "u_resolution"), grid_.resolution);
  }

  // Lit voxels start at -ln(F_t P), all others unreached.
  void initialize() const {
    const GLuint zero = 0;
    const auto r = static_cast<GLuint>(grid_.resolution);
    glClearNamedBufferData(flux_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingLabels, voxelizer_.labels_buffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingFlips, flux_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingDistances, solver_.distances_buffer());
    light_gbuffer_.bind_textures();
    glUseProgram(flux_program_.id());
    set_grid_uniforms(flux_program_.id());
    glUniform1f(glGetUniformLocation(flux_program_.id(), "u_flux_unit"), flux_unit_);
    const auto size = static_cast<GLuint>(light_gbuffer_.size());
    const std::vector<shader::LightGPU>& lights = light_gbuffer_.views().lights;
    for (std::size_t l = 0; l < lights.size(); ++l) {
      // All layers framing the translucent objects: 1 (directional, point/spot frustum) or 6 (cube faces).
      glUniform1i(glGetUniformLocation(flux_program_.id(), "u_light"), static_cast<GLint>(l));
      glDispatchCompute((size + 7) / 8, (size + 7) / 8, static_cast<GLuint>(lights[l].views.y));
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingSigmaT, field_.buffer());
    glUseProgram(distances_program_.id());
    set_grid_uniforms(distances_program_.id());
    glUniform1f(glGetUniformLocation(distances_program_.id(), "u_flux_unit"), flux_unit_);
    glUniform1f(glGetUniformLocation(distances_program_.id(), "u_entry_depth"),
                static_cast<float>(params_.number("entry_depth")));
    glDispatchCompute((r + 3) / 4, (r + 3) / 4, (r + 3) / 4);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  // exp(-n) into the 3D texture.
  void radiance() const {
    const auto r = static_cast<GLuint>(grid_.resolution);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingLabels, voxelizer_.labels_buffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingDistances, solver_.distances_buffer());
    glBindImageTexture(kImageRadiance, radiance_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glUseProgram(radiance_program_.id());
    set_grid_uniforms(radiance_program_.id());
    glDispatchCompute((r + 3) / 4, (r + 3) / 4, (r + 3) / 4);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }

  void shade(const FrameContext& context) const {
    light_gbuffer_.bind_textures();
    glBindTextureUnit(kTextureRadiance, radiance_);
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    const GLuint p = shade_program_.id();
    glUseProgram(p);
    glUniform3fv(glGetUniformLocation(p, "u_origin"), 1, &grid_.origin.x);
    glUniform1f(glGetUniformLocation(p, "u_grid_size"), grid_.voxel_size * static_cast<float>(grid_.resolution));
    glDispatchCompute(static_cast<GLuint>((width_ + 7) / 8), static_cast<GLuint>((height_ + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }

  const ParamValues& params_;
  render::LightGBuffer light_gbuffer_;
  TranslucentTriangles triangles_;
  VoxelGrid grid_;
  TriangleSource source_;  // the renderer's own vertex and index buffers (deformed in place every frame)
  Voxelizer voxelizer_;
  CoefficientField field_;
  RelaxationSolver solver_;
  gpu::ShaderProgram flux_program_, distances_program_, radiance_program_, shade_program_;
  GLuint flux_ = 0, radiance_ = 0;
  float flux_unit_ = 1.0f;
  RelaxationStats stats_;
  int width_ = 0, height_ = 0;
  bool solve_needed_ = true;
};

}  // namespace

std::unique_ptr<Method> create_voxel_paths(const MethodSetup& setup) {
  return std::make_unique<VoxelPaths>(setup.scene, setup.scene_gpu);
}

}  // namespace lucent::methods
