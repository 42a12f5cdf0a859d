// hybrid_io.h: the hybrid method's own GPU data: its uniform block (at LUCENT_BINDING_METHOD), the local
// pattern's layout and the binding points of its passes and of its sampler (texture_space/irradiance_sampler.h),
// inside the method ranges of shared/bindings.h (C++ and GLSL).
#ifndef LUCENT_METHODS_HYBRID_IO_H
#define LUCENT_METHODS_HYBRID_IO_H
#include "shared/shader_io.h"
#include "shared/tsis_samples.h"

#define LUCENT_IMAGE_HYBRID_SOURCE 2      // RGBA32F: E' pyramid level read (mip reduction, row CDF)
#define LUCENT_IMAGE_HYBRID_TARGET 3      // RGBA32F: E' pyramid level written (irradiance: level 0)
#define LUCENT_IMAGE_HYBRID_SUM 4         // RGBA32F: rgb the sum of the shaded radiance over frames, a their count
#define LUCENT_TEX_HYBRID_PYRAMID 8       // the E' pyramid with all its levels (sampling)
#define LUCENT_BINDING_HYBRID_SAMPLES 20  // vec4 total, TsisSampleGPU[] (std430): the frame's N global samples
#define LUCENT_BINDING_HYBRID_ROW_CDF 21  // float[P * P + P] (std430): row-major CDF (order row-major)
#define LUCENT_BINDING_HYBRID_PATTERN 22  // vec4[materials * (L + 2)] (std430): the local pattern per material

// Bounds of the shade pass's loops (its parameters' ranges, hybrid_info.cpp): Mesa llvmpipe ends a shader's loops
// after 65,535 iterations in all, which hybrid.cpp checks against N and the lights times the pattern.
#define LUCENT_HYBRID_MAX_SAMPLES 4096
#define LUCENT_HYBRID_MAX_RINGS 64
#define LUCENT_HYBRID_MAX_RING_POINTS 64

LUCENT_SHADER_BEGIN

struct HybridGPU {
  ivec4 counts;  // x: global samples N; y: rings L; z: points per ring C; w: entries per material (L + 2)
  vec4 split;    // x: K [1/scene unit]; yzw: unused
};

LUCENT_SHADER_END

// The local pattern of material m at pattern[m * (L + 2) + i]: i = 0: (R_p [scene units], 0, 0, 0); i = 1 + j,
// j = 0..L: hybrid_ring(..., j, L, C) of bssrdf/hybrid_split.h (j = 0 the centre): per band the weight of the
// stratum's mean transmitted irradiance, and the ring's radius [scene units].

#if defined(__cplusplus)
static_assert(sizeof(lucent::shader::HybridGPU) == 32);
static_assert(LUCENT_IMAGE_HYBRID_SOURCE >= LUCENT_METHOD_IMAGE_FIRST && LUCENT_IMAGE_HYBRID_SUM <= LUCENT_METHOD_IMAGE_LAST);
static_assert(LUCENT_TEX_HYBRID_PYRAMID >= LUCENT_METHOD_TEX_FIRST && LUCENT_TEX_HYBRID_PYRAMID <= LUCENT_METHOD_TEX_LAST);
static_assert(LUCENT_BINDING_HYBRID_SAMPLES >= LUCENT_METHOD_STORAGE_FIRST &&
              LUCENT_BINDING_HYBRID_PATTERN <= LUCENT_METHOD_STORAGE_LAST);
#endif

#endif
