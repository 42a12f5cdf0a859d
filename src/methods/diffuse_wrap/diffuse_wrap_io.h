// diffuse_wrap_io.h: the diffuse-wrap method's own GPU data: its uniform block (at LUCENT_BINDING_METHOD; C++ and
// GLSL). It binds no other slot.
#ifndef LUCENT_METHODS_DIFFUSE_WRAP_IO_H
#define LUCENT_METHODS_DIFFUSE_WRAP_IO_H
#include "shared/shader_io.h"

LUCENT_SHADER_BEGIN

struct DiffuseWrapGPU {
  vec4 shading;  // x: wrap w in [0, 1]; yzw: unused
};

LUCENT_SHADER_END

#if defined(__cplusplus)
static_assert(sizeof(lucent::shader::DiffuseWrapGPU) == 16);
#endif

#endif
