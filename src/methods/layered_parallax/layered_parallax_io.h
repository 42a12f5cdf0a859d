// layered_parallax_io.h: the layered-parallax method's own GPU data: its uniform block (at LUCENT_BINDING_METHOD)
// and binding points, inside the method ranges of shared/bindings.h (C++ and GLSL).
#ifndef LUCENT_METHODS_LAYERED_PARALLAX_IO_H
#define LUCENT_METHODS_LAYERED_PARALLAX_IO_H
#include "shared/shader_io.h"

#define LUCENT_TEX_LPAR_OUTER_BASE 8     // RGBA32F, repeating: rgb outer base colour, a see-through weight
#define LUCENT_TEX_LPAR_OUTER_NORMAL 9   // RGBA32F, repeating: rgb tangent-space normal of the outer layer
#define LUCENT_TEX_LPAR_INNER_BASE 10    // RGBA32F, repeating, mipmapped: rgb inner base colour
#define LUCENT_TEX_LPAR_LIGHT_MAP 11     // RGBA32F array (layer = object index): rgb irradiance, a coverage
#define LUCENT_TEX_LPAR_SURFACE 12       // RGBA32F per camera pixel: xy texture coordinates, z object index + 1
#define LUCENT_TEX_LPAR_GRADIENT_U 13    // RGBA32F: xyz the surface gradient of u [1/scene unit]
#define LUCENT_TEX_LPAR_GRADIENT_V 14    // RGBA32F: xyz the surface gradient of v
#define LUCENT_IMAGE_LPAR_BLURRED 2      // RGBA32F array: the light map a blur pass writes
#define LUCENT_IMAGE_LPAR_SUM 3          // RGBA32F: rgb the sum of the shaded radiance over frames, a their count

LUCENT_SHADER_BEGIN

struct LayeredParallaxGPU {
  vec4 layers;  // x: inner depth d [scene units]; y: texture tiling; z: light-map blur radius of this pass
                // [texture units]; w: inner blur [texture units per scene unit of transmission distance]
  ivec4 counts; // x: light-map size; y: light-map layers; z: pass index; w: unused
};

LUCENT_SHADER_END

#if defined(__cplusplus)
static_assert(sizeof(lucent::shader::LayeredParallaxGPU) == 32);
static_assert(LUCENT_TEX_LPAR_OUTER_BASE >= LUCENT_METHOD_TEX_FIRST && LUCENT_TEX_LPAR_GRADIENT_V <= LUCENT_METHOD_TEX_LAST);
static_assert(LUCENT_IMAGE_LPAR_BLURRED >= LUCENT_METHOD_IMAGE_FIRST && LUCENT_IMAGE_LPAR_SUM <= LUCENT_METHOD_IMAGE_LAST);
#endif

#endif
