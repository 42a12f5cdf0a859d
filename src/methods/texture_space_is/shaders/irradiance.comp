// irradiance.comp: stage 1 of texture-space importance sampling (Chang et al. 2008, Eq. 7): per atlas texel the
// irradiance from every light, shadowed (light G-buffer), times the Fresnel transmittance into the medium and the
// area ratio A_S / A_T of the texel (normal_ratio.w, max(w, 0): gutter and touched-only texels carry no area).
// Writes E' (rgb per band, a = their mean, the sampled density) into level 0 of the pyramid.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/fresnel.h"
#include "methods/texture_space_is/texture_space_is_io.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { TextureSpaceIsGPU method; };
layout(binding = TSIS_TEX_POSITION) uniform sampler2D texel_position;
layout(binding = TSIS_TEX_NORMAL_RATIO) uniform sampler2D texel_normal_ratio;
layout(rgba32f, binding = LUCENT_IMAGE_TSIS_TARGET) uniform writeonly image2D level0;
layout(std430, binding = LUCENT_BINDING_COUNTERS) buffer CounterBlock { CountersGPU counters; };

void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(t, ivec2(method.atlas.x)))) return;
  vec4 p = texelFetch(texel_position, t, 0);
  vec4 nr = texelFetch(texel_normal_ratio, t, 0);
  float area = max(nr.w, 0.0f);
  vec3 E = vec3(0.0f);
  if (p.w > 0.5f && area > 0.0f) {
    ObjectGPU object = objects[int(p.w) - 1];
    float eta = materials[object.info.x].sigma_a.w;
    vec3 n = normalize(nr.xyz);
    for (int l = 0; l < frame.light_counts.x; ++l) {
      vec3 w_l;
      vec3 E_l = light_incidence(frame.lights[l], p.xyz, w_l);
      float cos_l = dot(n, w_l);
      if (cos_l <= 0.0f) continue;
      E += E_l * cos_l * fresnel_transmittance(eta, cos_l) * light_visibility(l, p.xyz, n);
    }
  }
  vec3 E_prime = E * area;
  float a = (E_prime.r + E_prime.g + E_prime.b) / 3.0f;
  if (a > 0.0f) atomicAdd(counters.method_counts[0], 1u);
  imageStore(level0, t, vec4(E_prime, a));
}
