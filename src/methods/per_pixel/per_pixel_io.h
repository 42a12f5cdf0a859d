// per_pixel_io.h: the per-pixel method's own GPU data: its uniform block (at LUCENT_BINDING_METHOD) and binding
// points, inside the method ranges of shared/bindings.h (C++ and GLSL).
#ifndef LUCENT_METHODS_PER_PIXEL_IO_H
#define LUCENT_METHODS_PER_PIXEL_IO_H
#include "shared/shader_io.h"

#define LUCENT_IMAGE_PER_PIXEL_SUM 2  // RGBA32F: rgb the sum of B over the accumulated frames, a their count

LUCENT_SHADER_BEGIN

struct PerPixelGPU {
  ivec4 counts;  // x: samples N per band and light; yzw: unused
};

LUCENT_SHADER_END

#if defined(__cplusplus)
static_assert(sizeof(lucent::shader::PerPixelGPU) == 16);
static_assert(LUCENT_IMAGE_PER_PIXEL_SUM >= LUCENT_METHOD_IMAGE_FIRST && LUCENT_IMAGE_PER_PIXEL_SUM <= LUCENT_METHOD_IMAGE_LAST);
#endif

#endif
