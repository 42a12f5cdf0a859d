// denoise_io.h: the denoising stage's GPU data (C++ and GLSL): its uniform block and its slots inside the denoise
// ranges of shared/bindings.h (the stage runs after the method's passes, in slots the method no longer uses).
#ifndef LUCENT_DENOISE_IO_H
#define LUCENT_DENOISE_IO_H
#include "shared/shader_io.h"

#define LUCENT_BINDING_DENOISE 12                // DenoiseGPU (std140 uniform)
#define LUCENT_TEX_DENOISE_INPUT 32              // the method's radiance (rgb) and coverage (a) this frame
#define LUCENT_TEX_DENOISE_HISTORY 33            // the previous frame's combined estimate (rgb; a: its frames)
#define LUCENT_TEX_DENOISE_PREVIOUS_POSITION 34  // the previous frame's camera G-buffer: position, w object + 1
#define LUCENT_TEX_DENOISE_PREVIOUS_NORMAL 35    // and normal
#define LUCENT_TEX_DENOISE_FILTER 36             // the wavelet pass's input: rgb radiance / albedo, a: variance
#define LUCENT_TEX_DENOISE_COMBINED 37           // this frame's combined estimate (rgb; a: its frames)
#define LUCENT_TEX_DENOISE_PREVIOUS_AVERAGE 38   // the method's average of the previous frame (rgb)
#define LUCENT_TEX_DENOISE_PREVIOUS_MOMENTS 39   // the previous frame's luminance moments (as the image below)
#define LUCENT_TEX_DENOISE_MOMENTS 40            // this frame's
#define LUCENT_IMAGE_DENOISE_FROZEN 2            // RGBA32F: the history kept at the last restart (rgb; a: frames)
#define LUCENT_IMAGE_DENOISE_OUTPUT 3            // RGBA32F: what the pass writes
#define LUCENT_IMAGE_DENOISE_MOMENTS 4           // RGBA32F: per pixel, over the frames behind the combined estimate,
                                                 // x the sum of one frame's luminance / albedo, y of its square, z
                                                 // the frames

// DenoiseGPU.state.x
#define LUCENT_DENOISE_KEEP 0       // the method added frames to its average: the kept history still applies
#define LUCENT_DENOISE_REPROJECT 1  // the method started its average again after a camera move: reproject
#define LUCENT_DENOISE_DROP 2       // it started again for another reason (an edit): no history

LUCENT_SHADER_BEGIN

// The stage's uniform block (std140, 112 bytes).
struct DenoiseGPU {
  mat4 previous_clip_from_world;  // the previous frame's camera
  vec4 weights;  // x: sigma_luminance [std devs], y: normal power, z: sigma_plane [pixel footprints per pixel],
                 // w: the angle one pixel subtends [radians] (footprint = distance x w)
  vec4 history;  // x: frames of history kept at most, y: frames in the method's average, z: fade frames,
                 // w: the wavelet pass's step [pixels]
  ivec4 state;   // x: LUCENT_DENOISE_*, y: the wavelet pass's index, zw: unused
};

LUCENT_SHADER_END

#if defined(__cplusplus)
static_assert(sizeof(lucent::shader::DenoiseGPU) == 112);
#endif

#endif
