// vertex_irradiance.comp: per vertex of the global basis, a gather over the texels of its triangles
// (Lensch et al. 2002, Eq. 10 and Section 6.1): E^g_i = sum dual_i(x_c) A E(texel) and B^d_i = sum w_i E(texel).
#include "shared/shader_io.h"
#include "methods/local_global/local_global_io.h"

layout(local_size_x = 64) in;
layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LocalGlobalGPU method; };
layout(binding = LUCENT_TEX_LG_ILLUMINATION) uniform sampler2D illumination;
layout(std430, binding = LUCENT_BINDING_LG_VERTEX_OFFSETS) readonly buffer Offsets { uint vertex_offsets[]; };
layout(std430, binding = LUCENT_BINDING_LG_VERTEX_TEXELS) readonly buffer Texels { uvec4 vertex_texels[]; };
layout(std430, binding = LUCENT_BINDING_LG_VERTEX_IRRADIANCE) writeonly buffer Irradiance { vec4 vertex_irradiance[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(method.counts.y)) return;
  vec3 E = vec3(0.0f), B = vec3(0.0f);
  for (uint k = vertex_offsets[i]; k < vertex_offsets[i + 1u]; ++k) {
    uvec4 a = vertex_texels[2u * k];
    vec3 w = uintBitsToFloat(vertex_texels[2u * k + 1u].xyz);
    vec3 e = texelFetch(illumination, ivec2(int(a.x & 0xffffu), int(a.x >> 16u)), 0).rgb;
    E += uintBitsToFloat(a.y) * e;
    B += w * e;
  }
  vertex_irradiance[2u * i] = vec4(E, 0.0f);
  vertex_irradiance[2u * i + 1u] = vec4(B, 0.0f);
}
