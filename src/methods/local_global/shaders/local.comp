// local.comp: the local response (Lensch et al. 2002, Eq. 15): per covered atlas texel p, B_l(p) = sum over the
// 7 x 7 offsets d of K_{p - d}(d) E(p - d), the kernels stored in scatter form (the response at q + d to unit
// irradiance on q), so the sum gathers from the sources around p. 0 on texels without a covered centre.
#include "shared/shader_io.h"
#include "methods/local_global/local_global_io.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LocalGlobalGPU method; };
layout(binding = LUCENT_TEX_LG_ILLUMINATION) uniform sampler2D illumination;
layout(binding = LUCENT_TEX_LG_TEXEL_INDEX) uniform isampler2D texel_index;
layout(std430, binding = LUCENT_BINDING_LG_KERNELS) readonly buffer Kernels { float kernels[]; };
layout(rgba32f, binding = LUCENT_IMAGE_LG_LOCAL) uniform writeonly image2D local_radiosity;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  int size = method.counts.x;
  if (any(greaterThanEqual(p, ivec2(size)))) return;
  vec3 B = vec3(0.0f);
  if (texelFetch(texel_index, p, 0).r >= 0) {
    for (int dy = -3; dy <= 3; ++dy)
      for (int dx = -3; dx <= 3; ++dx) {
        ivec2 q = p - ivec2(dx, dy);
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(size)))) continue;
        int index = texelFetch(texel_index, q, 0).r;
        if (index < 0) continue;
        int base = (index * 49 + (dy + 3) * 7 + (dx + 3)) * 3;
        vec3 K = vec3(kernels[base], kernels[base + 1], kernels[base + 2]);
        B += K * texelFetch(illumination, q, 0).rgb;
      }
  }
  imageStore(local_radiosity, p, vec4(B, 0.0f));
}
