// vertex_irradiance_sum.comp: per vertex of the global basis, the sum of its chunks' parts of E^g_i and B^d_i
// (vertex_irradiance.comp); at most LUCENT_LG_VERTEX_CHUNK chunks a vertex (checked on the CPU).
#include "shared/shader_io.h"
#include "methods/local_global/local_global_io.h"

layout(local_size_x = 64) in;
layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LocalGlobalGPU method; };
layout(std430, binding = LUCENT_BINDING_LG_VERTEX_CHUNKS) readonly buffer VertexChunks { uint vertex_chunks[]; };
layout(std430, binding = LUCENT_BINDING_LG_CHUNK_SUMS) readonly buffer Sums { vec4 chunk_sums[]; };
layout(std430, binding = LUCENT_BINDING_LG_VERTEX_IRRADIANCE) writeonly buffer Irradiance { vec4 vertex_irradiance[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(method.counts.y)) return;
  vec4 E = vec4(0.0f), B = vec4(0.0f);
  // loop bound: LUCENT_LG_VERTEX_CHUNK; local_global.cpp refuses a vertex of more chunks
  for (uint c = vertex_chunks[i]; c < vertex_chunks[i + 1u]; ++c) {
    E += chunk_sums[2u * c];
    B += chunk_sums[2u * c + 1u];
  }
  vertex_irradiance[2u * i] = E;
  vertex_irradiance[2u * i + 1u] = B;
}
