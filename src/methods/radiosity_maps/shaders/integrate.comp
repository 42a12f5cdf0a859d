// integrate.comp: step 2 of Dal Corso et al. 2015 (Fig. 3): the scattered radiosity B(x_o) of every texel of
// the K map views from all lights (common/light_sampling.glsl). Each texel accumulates (sum of B over frames,
// number of frames).
#include "common/frame.glsl"
#include "methods/radiosity_maps/shaders/method_block.glsl"
#include "common/lights.glsl"
#include "common/light_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(binding = LUCENT_TEX_MAP_POSITION) uniform sampler2DArray map_position;
layout(binding = LUCENT_TEX_MAP_NORMAL) uniform sampler2DArray map_normal;
#if defined(LUCENT_MATERIAL_MAPS)
layout(binding = LUCENT_TEX_MAP_UV) uniform sampler2DArray map_uv;
#endif
layout(rgba32f, binding = LUCENT_IMAGE_RADIOSITY) uniform image2DArray radiosity;
layout(std430, binding = LUCENT_BINDING_COUNTERS) buffer CounterBlock { CountersGPU counters; };

void main() {
  ivec3 texel = ivec3(gl_GlobalInvocationID);
  int size = method.counts.z;
  if (texel.x >= size || texel.y >= size || texel.z >= method.counts.x) return;
  vec4 previous = frame.seeds.z != 0u ? vec4(0.0f) : imageLoad(radiosity, texel);
  vec4 p_o = texelFetch(map_position, texel, 0);
  if (p_o.w < 0.5f) {
    imageStore(radiosity, texel, vec4(0.0f));
    return;
  }
  atomicAdd(counters.method_counts[0], 1u);  // covered map texels
  vec3 n_o = normalize(texelFetch(map_normal, texel, 0).xyz);
#if defined(LUCENT_MATERIAL_MAPS)
  vec2 uv_o = texelFetch(map_uv, texel, 0).xy;
#else
  vec2 uv_o = vec2(0.0f);
#endif
  vec3 B = scattered_radiosity(int(p_o.w) - 1, p_o.xyz, n_o, uv_o, uint(texel.y * size + texel.x), uint(texel.z),
                               method.counts.y);
  imageStore(radiosity, texel, previous + vec4(B, 1.0f));
}
