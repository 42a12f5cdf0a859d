// light_gbuffer.cpp: see light_gbuffer.h.
#include "render/light_gbuffer.h"

#include <algorithm>

#include "gpu/gl_debug.h"

namespace lucent::render {

std::string light_sampling_defines(const Scene& scene) {
  return scene.point_lights.empty() ? "#define LUCENT_DIRECTIONAL_LIGHTS_ONLY 1\n" : "";
}

LightGBuffer::LightGBuffer(const Scene& scene, const SceneGpu& scene_gpu, int size)
    : size_(size),
      views_(build_light_views(scene, scene_gpu.translucent_bounds(), scene_gpu.scene_bounds(), size)),
      gbuffer_(size, size, std::max<int>(1, static_cast<int>(views_.views.size())), "light G-buffer"),
      program_(gpu::ShaderProgram::graphics("gbuffer/gbuffer.vert", "gbuffer/layered_views.geom",
                                            "gbuffer/gbuffer.frag")) {}

void LightGBuffer::fill_frame(shader::FrameGPU& frame) const {
  frame.counts.x = light_count();
  frame.sizes.y = size_;
  frame.extra_counts.x = static_cast<int>(views_.views.size());
  std::copy(views_.lights.begin(), views_.lights.end(), frame.lights);
  std::copy(views_.views.begin(), views_.views.end(), frame.light_views);
}

void LightGBuffer::render(const SceneGpu& scene_gpu, gpu::GpuTimer& timer) const {
  gpu::DebugGroup group("light_gbuffer");
  timer.begin("light_gbuffer");
  gbuffer_.begin_pass();
  glUseProgram(program_.id());
  glUniform1i(glGetUniformLocation(program_.id(), "u_view_set"), 0);
  if (!views_.views.empty()) scene_gpu.draw_all();
  timer.end();
}

void LightGBuffer::bind_textures() const {
  gbuffer_.bind_textures(LUCENT_TEX_LIGHT_POSITION, LUCENT_TEX_LIGHT_NORMAL, LUCENT_TEX_LIGHT_DEPTH);
}

std::size_t LightGBuffer::gpu_memory_bytes() const {  // RGBA32F position + RGBA16F normal + DEPTH32F
  return static_cast<std::size_t>(size_) * static_cast<std::size_t>(size_) *
         static_cast<std::size_t>(gbuffer_.layers()) * (16 + 8 + 4);
}

}  // namespace lucent::render
