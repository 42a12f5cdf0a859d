// vertex_irradiance.comp: one chunk of a vertex's texels per invocation (Lensch et al. 2002, Eq. 10 and Section
// 6.1): the chunk's part of E^g_i = sum dual_i(x_c) A E(texel) and of B^d_i = sum w_i E(texel). A chunk holds at
// most LUCENT_LG_VERTEX_CHUNK texels (llvmpipe's loop limit); vertex_irradiance_sum.comp adds a vertex's chunks.
#include "shared/shader_io.h"
#include "methods/local_global/local_global_io.h"

layout(local_size_x = 64) in;
layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LocalGlobalGPU method; };
layout(binding = LUCENT_TEX_LG_ILLUMINATION) uniform sampler2D illumination;
layout(std430, binding = LUCENT_BINDING_LG_CHUNKS) readonly buffer Chunks { uvec2 chunks[]; };
layout(std430, binding = LUCENT_BINDING_LG_VERTEX_TEXELS) readonly buffer Texels { uvec4 vertex_texels[]; };
layout(std430, binding = LUCENT_BINDING_LG_CHUNK_SUMS) writeonly buffer Sums { vec4 chunk_sums[]; };

void main() {
  uint c = gl_GlobalInvocationID.x;
  if (c >= uint(method.options.y)) return;
  uvec2 range = chunks[c];
  vec3 E = vec3(0.0f), B = vec3(0.0f);
  // loop bound: LUCENT_LG_VERTEX_CHUNK; local_global.cpp cuts each vertex's texels into chunks of at most this many
  for (uint k = range.x; k < range.y; ++k) {
    uvec4 a = vertex_texels[2u * k];
    vec3 w = uintBitsToFloat(vertex_texels[2u * k + 1u].xyz);
    vec3 e = texelFetch(illumination, ivec2(int(a.x & 0xffffu), int(a.x >> 16u)), 0).rgb;
    E += uintBitsToFloat(a.y) * e;
    B += w * e;
  }
  chunk_sums[2u * c] = vec4(E, 0.0f);
  chunk_sums[2u * c + 1u] = vec4(B, 0.0f);
}
