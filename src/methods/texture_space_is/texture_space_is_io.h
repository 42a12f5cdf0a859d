// texture_space_is_io.h: the texture-space importance sampling method's own GPU data: its uniform block (at
// LUCENT_BINDING_METHOD) and the binding points of its sampler (texture_space/irradiance_sampler.h; the sample
// layout is shared/tsis_samples.h), inside the method ranges of shared/bindings.h (C++ and GLSL).
#ifndef LUCENT_METHODS_TEXTURE_SPACE_IS_IO_H
#define LUCENT_METHODS_TEXTURE_SPACE_IS_IO_H
#include "shared/shader_io.h"
#include "shared/tsis_samples.h"

#define LUCENT_IMAGE_TSIS_SOURCE 2       // RGBA32F: E' pyramid level read (mip reduction), level 0 (irradiance, row CDF)
#define LUCENT_IMAGE_TSIS_TARGET 3       // RGBA32F: E' pyramid level written (irradiance: level 0)
#define LUCENT_IMAGE_TSIS_SUM 4          // RGBA32F: rgb the sum of the shaded radiance over frames, a their count
#define LUCENT_TEX_TSIS_PYRAMID 8        // the E' pyramid with all its levels (sampling)
#define LUCENT_BINDING_TSIS_SAMPLES 20   // TsisSamplesGPU (std430): the frame's N samples
#define LUCENT_BINDING_TSIS_ROW_CDF 21   // float[size * size + size] (std430): row-major CDF (order row-major)
#define LUCENT_TSIS_MAX_SAMPLES 4096     // bound of the shade pass's sample loop: N's range (texture_space_is_info.cpp)

LUCENT_SHADER_BEGIN

struct TextureSpaceIsGPU {
  ivec4 counts;  // x: samples N; y: order (LUCENT_TSIS_ORDER_*); z: pyramid size P (power of two); w: levels
  ivec4 atlas;   // x: atlas size (texels of the texture-space G-buffer, <= P); y: pyramid level being reduced
};

LUCENT_SHADER_END

#if defined(__cplusplus)
static_assert(sizeof(lucent::shader::TextureSpaceIsGPU) == 32);
static_assert(LUCENT_IMAGE_TSIS_SOURCE >= LUCENT_METHOD_IMAGE_FIRST && LUCENT_IMAGE_TSIS_SUM <= LUCENT_METHOD_IMAGE_LAST);
static_assert(LUCENT_TEX_TSIS_PYRAMID >= LUCENT_METHOD_TEX_FIRST && LUCENT_TEX_TSIS_PYRAMID <= LUCENT_METHOD_TEX_LAST);
static_assert(LUCENT_BINDING_TSIS_SAMPLES >= LUCENT_METHOD_STORAGE_FIRST &&
              LUCENT_BINDING_TSIS_ROW_CDF <= LUCENT_METHOD_STORAGE_LAST);
#endif

#endif
