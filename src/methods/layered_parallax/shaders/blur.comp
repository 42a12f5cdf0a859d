// blur.comp: one Poisson-disc pass over the light map (Norberg 2010, Section 3.2: several passes of a small disc
// instead of one large one, whose taps would copy the pattern around each texel). Texels no triangle covered
// (a = 0) take no weight, so the light spreads over chart borders instead of darkening them.
#include "shared/shader_io.h"
#include "methods/layered_parallax/layered_parallax_io.h"
#include "methods/layered_parallax/shaders/poisson_disc.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LayeredParallaxGPU method; };
layout(binding = LUCENT_TEX_LPAR_LIGHT_MAP) uniform sampler2DArray source;
layout(rgba32f, binding = LUCENT_IMAGE_LPAR_BLURRED) uniform writeonly image2DArray target;

void main() {
  ivec3 texel = ivec3(gl_GlobalInvocationID.xyz);
  int size = method.counts.x;
  if (texel.x >= size || texel.y >= size) return;
  vec2 uv = (vec2(texel.xy) + 0.5f) / float(size);
  vec4 sum = vec4(0.0f);
  for (int i = 0; i < kPoissonTaps; ++i) {
    // Premultiplied (rgb = E a), so bilinear taps across a chart border weigh E by the covered fraction.
    sum += textureLod(source, vec3(uv + method.layers.z * kPoissonDisc[i], float(texel.z)), 0.0f);
  }
  imageStore(target, texel, sum.a > 0.0f ? vec4(sum.rgb / sum.a, 1.0f) : vec4(0.0f));
}
