// irradiance.comp: stage 1 of texture-space importance sampling (Chang et al. 2008, Eq. 7): per atlas texel the
// irradiance from every light, shadowed (light G-buffer), times the Fresnel transmittance into the medium and the
// area ratio A_S / A_T of the texel (normal_ratio.w, max(w, 0): gutter and touched-only texels carry no area).
// Writes E' (rgb per band, a = their mean, the sampled density) into level 0 of the pyramid. Slots and the
// texture G-buffer units come from the caller's defines (texture_space/irradiance_sampler.h).
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/fresnel.h"
#include "shared/tsis_samples.h"
#include "texture_space/transmitted_irradiance.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(location = 0) uniform int atlas_size;
layout(binding = TSIS_TEX_POSITION) uniform sampler2D texel_position;
layout(binding = TSIS_TEX_NORMAL_RATIO) uniform sampler2D texel_normal_ratio;
layout(rgba32f, binding = TSIS_IMAGE_TARGET) uniform writeonly image2D level0;
layout(std430, binding = LUCENT_BINDING_COUNTERS) buffer CounterBlock { CountersGPU counters; };

void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(t, ivec2(atlas_size)))) return;
  vec4 p = texelFetch(texel_position, t, 0);
  vec4 nr = texelFetch(texel_normal_ratio, t, 0);
  float area = max(nr.w, 0.0f);
  vec3 E = vec3(0.0f);
  if (p.w > 0.5f && area > 0.0f) {
    ObjectGPU object = objects[int(p.w) - 1];
    float eta = materials[object.info.x].sigma_a.w;
    E = transmitted_irradiance(p.xyz, normalize(nr.xyz), eta);
  }
  vec3 E_prime = E * area;
  float a = (E_prime.r + E_prime.g + E_prime.b) / 3.0f;
  if (a > 0.0f) atomicAdd(counters.method_counts[0], 1u);
  imageStore(level0, t, vec4(E_prime, a));
}
