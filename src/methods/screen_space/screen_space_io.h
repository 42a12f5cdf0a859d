// screen_space_io.h: the screen-space method's own GPU data: its uniform block (at LUCENT_BINDING_METHOD), its
// kernel buffer and its images, inside the method ranges of shared/bindings.h (C++ and GLSL).
#ifndef LUCENT_METHODS_SCREEN_SPACE_IO_H
#define LUCENT_METHODS_SCREEN_SPACE_IO_H
#include "shared/shader_io.h"

#define LUCENT_IMAGE_SCREEN_SPACE_IRRADIANCE 2  // RGBA32F: rgb transmitted irradiance E_t, a 1 on translucent pixels
#define LUCENT_IMAGE_SCREEN_SPACE_HORIZONTAL 3  // RGBA32F: after the horizontal pass
#define LUCENT_IMAGE_SCREEN_SPACE_BLURRED 4     // RGBA32F: after the vertical pass
#define LUCENT_BINDING_SCREEN_SPACE_KERNEL 20   // ScreenSpaceTapGPU[materials * kScreenSpaceMaxTaps] (std430)

#define LUCENT_SCREEN_SPACE_MAX_TAPS 25

LUCENT_SHADER_BEGIN

struct ScreenSpaceGPU {
  ivec4 counts;  // x: taps per pass; y: profile (LUCENT_SCREEN_SPACE_PROFILE_*); z: 1 = transmittance through thin
                 // parts on; w: unused
  vec4 blur;     // x: depth threshold, in kernel radii, beyond which a tap is blended back to the centre; yzw: unused
};

// One tap of a material's 1D kernel: its weight per band (the taps of a band sum to 1) and its offset.
struct ScreenSpaceTapGPU {
  vec4 tap;  // rgb: weight per band; w: offset from the centre [scene units], along the pass's image axis
};

LUCENT_SHADER_END

#if defined(__cplusplus)
static_assert(sizeof(lucent::shader::ScreenSpaceGPU) == 32);
static_assert(sizeof(lucent::shader::ScreenSpaceTapGPU) == 16);
static_assert(LUCENT_IMAGE_SCREEN_SPACE_IRRADIANCE >= LUCENT_METHOD_IMAGE_FIRST &&
              LUCENT_IMAGE_SCREEN_SPACE_BLURRED <= LUCENT_METHOD_IMAGE_LAST);
static_assert(LUCENT_IMAGE_SCREEN_SPACE_HORIZONTAL >= LUCENT_METHOD_IMAGE_FIRST &&
              LUCENT_IMAGE_SCREEN_SPACE_HORIZONTAL <= LUCENT_METHOD_IMAGE_LAST);
static_assert(LUCENT_BINDING_SCREEN_SPACE_KERNEL >= LUCENT_METHOD_STORAGE_FIRST &&
              LUCENT_BINDING_SCREEN_SPACE_KERNEL <= LUCENT_METHOD_STORAGE_LAST);
#endif

#endif
