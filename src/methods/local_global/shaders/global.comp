// global.comp: the global response per vertex (Lensch et al. 2002, Eqs. 9 and 11 with Section 5.4's direct
// radiosity): B_j = B^d_j + sum_i F'_ij E^g_i per band over row j of the sparse matrix (diagonal zeroed).
#include "shared/shader_io.h"
#include "methods/local_global/local_global_io.h"

layout(local_size_x = 64) in;
layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LocalGlobalGPU method; };
layout(std430, binding = LUCENT_BINDING_LG_ROW_OFFSETS) readonly buffer Rows { uint row_offsets[]; };
layout(std430, binding = LUCENT_BINDING_LG_FORM_FACTORS) readonly buffer Factors { uvec4 form_factors[]; };
layout(std430, binding = LUCENT_BINDING_LG_VERTEX_IRRADIANCE) readonly buffer Irradiance { vec4 vertex_irradiance[]; };
layout(std430, binding = LUCENT_BINDING_LG_VERTEX_RADIOSITY) writeonly buffer Radiosity { vec4 vertex_radiosity[]; };

void main() {
  uint j = gl_GlobalInvocationID.x;
  if (j >= uint(method.counts.y)) return;
  vec3 B = vertex_irradiance[2u * j + 1u].rgb;
  // loop bound: checked; local_global.cpp refuses on llvmpipe a row of more form factors than the loop budget
  for (uint k = row_offsets[j]; k < row_offsets[j + 1u]; ++k) {
    uvec4 f = form_factors[k];
    B += uintBitsToFloat(f.yzw) * vertex_irradiance[2u * f.x].rgb;
  }
  vertex_radiosity[j] = vec4(B, 0.0f);
}
