// tsis_samples.h: what texture-space importance sampling (Chang et al. 2008, Section 3.2) hands to a shading pass,
// C++ and GLSL: one sample per drawn atlas texel with its estimator weight, and the two inverse-CDF orders. Written
// by shaders/texture_space/irradiance_sample.comp (texture_space/irradiance_sampler.h), read by the shading passes
// of the methods that use it (texture-space-is, hybrid). The binding slots are the using method's own.
#ifndef LUCENT_SHARED_TSIS_SAMPLES_H
#define LUCENT_SHARED_TSIS_SAMPLES_H
#include "shared/bridge.h"

#define LUCENT_TSIS_ORDER_MIPMAP 0
#define LUCENT_TSIS_ORDER_ROW_MAJOR 1

LUCENT_SHADER_BEGIN

// One sample of the frame: the texel it landed on and its estimator weight per band,
// E'(texel) E'_total,a / (E'_a(texel) N) (Eq. 10 with p = E'_a / E'_total,a; a = mean of the bands).
struct TsisSampleGPU {
  ivec4 texel;   // xy: texel of level 0; zw: unused
  vec4 weight;   // rgb: weight per band [irradiance x area]; a: unused
};

LUCENT_SHADER_END

#if defined(__cplusplus)
static_assert(sizeof(lucent::shader::TsisSampleGPU) == 32);
#endif

#endif
