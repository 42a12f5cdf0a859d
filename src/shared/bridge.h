// bridge.h: lets one header be compiled both as C++20 (through GLM) and as GLSL 4.50.
//
// The physics (Fresnel, BSSRDF models, random numbers) and the CPU-GPU data layouts are written once in
// headers that include this file. C++ sees them inside namespace lucent::shader with GLM's vector types;
// shaders see plain GLSL. The subset both languages accept: free functions on float/vec/uint, structs filled
// field by field (no constructors), float literals with an f suffix, no references, templates or STL.
#ifndef LUCENT_SHARED_BRIDGE_H
#define LUCENT_SHARED_BRIDGE_H

#if defined(__cplusplus)
#include <cstdint>
#include <glm/glm.hpp>
#define LUCENT_SHADER_BEGIN \
  namespace lucent::shader {  \
  using namespace glm;        \
  using uint = std::uint32_t;
#define LUCENT_SHADER_END }
#define LUCENT_INLINE inline
#define LUCENT_CONST inline constexpr
#elif defined(GL_core_profile)
#define LUCENT_SHADER_BEGIN
#define LUCENT_SHADER_END
#define LUCENT_INLINE
#define LUCENT_CONST const
#else
#error "bridge.h compiles as C++ or as GLSL core profile only"
#endif

#endif  // LUCENT_SHARED_BRIDGE_H
