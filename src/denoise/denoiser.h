// denoiser.h: the denoising stage the renderer runs after any method's passes, before tone mapping, when the
// scene's "denoise" settings enable it (denoise/denoise_params.h). It filters the method's radiance image in place:
//   1. temporal: the method's average combined with the history kept across the method's last restart,
//      reprojected through the camera's motion where a camera move restarted it (shaders/denoise/temporal.comp);
//   2. variance: the estimate divided by each surface's albedo, and its noise level from the moments of one
//      frame's luminance over the frames behind it, or from its neighbourhood's spread while few are
//      (variance.comp);
//   3. a-trous: `iterations` edge-stopping wavelet passes (atrous.comp);
//   4. modulate: times the albedo again (modulate.comp).
// The filter's luminance tolerance is a multiple of the estimate's noise, which the frames average away: a still
// view converges to the method's unbiased average.
// Its passes are timed as "denoise_temporal", "denoise_filter" and "denoise_modulate".
#pragma once
#include <cstddef>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "denoise/denoise_params.h"
#include "gpu/frame_profiler.h"
#include "gpu/gbuffer.h"
#include "gpu/shader_program.h"
#include "shared/shader_io.h"

namespace lucent::denoise {

// What the stage is given each frame.
struct DenoiseFrame {
  const shader::FrameGPU& frame;       // bound at LUCENT_BINDING_FRAME, with the scene's buffers
  const gpu::GBuffer& camera_gbuffer;  // this frame's
  GLuint radiance;                     // the method's RGBA32F image: read, then overwritten with the result
  int method_frames;                   // frames in the method's average (Method::accumulated_frames)
  bool method_restarted;               // the method started its average again this frame (N = 1)
  bool edited;                         // because the scene changed: no history is kept
  float fov_y_deg;                     // the camera's vertical field of view
  const DenoiseSettings& settings;
  gpu::FrameProfiler& profiler;
};

class Denoiser {
 public:
  // material_maps: the scene has textured materials (the camera G-buffer keeps texture coordinates, bound at
  // LUCENT_TEX_CAMERA_UV): the albedo maps divide the radiance per pixel.
  explicit Denoiser(bool material_maps);
  bool material_maps() const { return material_maps_; }
  ~Denoiser();
  Denoiser(const Denoiser&) = delete;
  Denoiser& operator=(const Denoiser&) = delete;

  void run(const DenoiseFrame& input);
  // Frames behind the combined estimate where the history applied in the last frame run (an upper bound per pixel:
  // pixels whose reprojection failed have only the method's frames).
  double history_frames() const { return history_frames_; }
  std::size_t gpu_memory_bytes() const;

 private:
  void resize(int width, int height);
  void release();

  bool material_maps_;
  gpu::ShaderProgram temporal_, variance_, atrous_, modulate_;
  GLuint block_ = 0;
  int width_ = 0, height_ = 0;
  // RGBA32F: the frozen history, the combined estimate and the moments (two each: this frame's and the previous
  // one's), the wavelet passes' two images, the method's previous average, the previous camera G-buffer's
  // position; RGBA16F its normal.
  GLuint frozen_ = 0, combined_[2] = {0, 0}, moments_[2] = {0, 0}, filter_[2] = {0, 0}, previous_average_ = 0,
         previous_position_ = 0, previous_normal_ = 0;
  int current_ = 0;  // combined_[current_] and moments_[current_] are this frame's
  bool has_previous_ = false;
  glm::mat4 previous_clip_from_world_{1.0f};
  double kept_frames_ = 0.0;     // L0 of the frozen history (its upper bound over pixels)
  double history_frames_ = 0.0;  // L0 + N of the last frame
};

}  // namespace lucent::denoise
