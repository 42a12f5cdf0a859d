// light_gbuffer.cpp: see light_gbuffer.h.
#include "render/light_gbuffer.h"

#include <algorithm>
#include <optional>

#include <fmt/format.h>

#include "bssrdf/photon_beam_diffusion.h"
#include "gpu/gl_debug.h"
#include "platform/gl_capabilities.h"

namespace lucent::render {

std::string light_sampling_defines(const Scene& scene) {
  std::string defines = scene.point_lights.empty() ? "#define LUCENT_DIRECTIONAL_LIGHTS_ONLY 1\n" : "";
  bool tabulated = false, multipole = false, one_model = true;
  std::optional<BssrdfModel> first;
  for (const SceneObject& object : scene.objects)
    if (object.translucent()) {
      const BssrdfModel model = object.material->model;
      tabulated = tabulated || model == BssrdfModel::Tabulated;
      multipole = multipole || model == BssrdfModel::Multipole;
      if (!first) first = model;
      one_model = one_model && model == *first;
    }
  if (tabulated) defines += "#define LUCENT_TABULATED_MODEL 1\n";  // bssrdf/model.h
  if (multipole) defines += "#define LUCENT_MULTIPOLE_MODEL 1\n";
  // One model for the whole scene: the shaders compile that model alone (bssrdf/model.h).
  if (first && one_model) defines += fmt::format("#define LUCENT_SCENE_MODEL {}\n", static_cast<int>(*first));
  if (has_material_maps(scene)) defines += "#define LUCENT_MATERIAL_MAPS 1\n";  // media/material_map.h
  for (const SceneObject& object : scene.objects)
    if (object.translucent() && !object.thickness.empty()) {  // geometry/thickness_field.h
      defines += "#define LUCENT_THICKNESS_FIELDS 1\n";
      break;
    }
  return defines;
}

std::uint64_t light_sampling_iterations_per_sample(const Scene& scene) {
  for (const SceneObject& object : scene.objects)
    if (object.translucent() && object.material->model == BssrdfModel::PhotonBeamDiffusion)
      return 1u + static_cast<std::uint64_t>(shader::kPhotonBeamSamples);
  return 1u;
}

void check_light_sampling_loops(std::string_view method, int light_count, std::uint64_t N,
                                std::uint64_t iterations_per_sample) {
  const std::uint64_t lights = static_cast<std::uint64_t>(std::max(light_count, 1));
  // Iterations: the light loop, its band loop, the sample loop inside.
  const std::uint64_t iterations = lights * (1u + 3u * (1u + N * iterations_per_sample));
  if (iterations <= platform::kLlvmpipeLoopBudget) return;  // formats the message only past it
  const std::uint64_t n_max = (platform::kLlvmpipeLoopBudget / lights - 4u) / (3u * iterations_per_sample);
  platform::check_loop_iterations(
      fmt::format("{}: N {} x 3 bands x {} lights{}", method, N, lights,
                  iterations_per_sample > 1 ? fmt::format(" x {} (photon beam)", iterations_per_sample) : ""),
      iterations, fmt::format("lower method.N to {}", n_max));
}

LightGBuffer::LightGBuffer(const Scene& scene, const SceneGpu& scene_gpu, int size)
    : size_(size),
      views_(build_light_views(scene, scene_gpu.translucent_bounds(), scene_gpu.scene_bounds(), size)),
      gbuffer_(size, size, std::max<int>(1, static_cast<int>(views_.views.size())), "light G-buffer"),
      layer_views_(views_.views, "light G-buffer views"),
      program_(gpu::layered_gbuffer_program()) {}

void LightGBuffer::fill_frame(shader::FrameGPU& frame) const {
  frame.light_counts.x = light_count();
  frame.light_counts.y = static_cast<int>(views_.views.size());
  frame.light_counts.z = size_;
  std::copy(views_.lights.begin(), views_.lights.end(), frame.lights);
  std::copy(views_.views.begin(), views_.views.end(), frame.light_views);
}

void LightGBuffer::render(const SceneGpu& scene_gpu, gpu::FrameProfiler& profiler) const {
  auto pass = profiler.pass("light_gbuffer");
  layer_views_.bind();
  gbuffer_.begin_pass();
  glUseProgram(program_.id());
  scene_gpu.draw_all(static_cast<int>(layer_views_.count()));
}

void LightGBuffer::bind_textures() const {
  gbuffer_.bind_textures(LUCENT_TEX_LIGHT_POSITION, LUCENT_TEX_LIGHT_NORMAL, LUCENT_TEX_LIGHT_DEPTH);
}

std::size_t LightGBuffer::gpu_memory_bytes() const {  // RGBA32F position + RGBA16F normal + DEPTH32F
  return static_cast<std::size_t>(size_) * static_cast<std::size_t>(size_) *
         static_cast<std::size_t>(gbuffer_.layers()) * (16 + 8 + 4);
}

}  // namespace lucent::render
