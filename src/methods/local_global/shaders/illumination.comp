// illumination.comp: the illumination map of the local-global method (Lensch et al. 2002, Section 6.1): per atlas
// texel whose centre lies on a triangle (texture G-buffer area ratio > 0), the irradiance entering the medium,
// F_t E from every light with shadows (texture_space/transmitted_irradiance.glsl); 0 elsewhere. E here is per
// unit area: the kernels and the dual weights carry the texel areas.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/fresnel.h"
#include "methods/local_global/local_global_io.h"
#include "texture_space/transmitted_irradiance.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LocalGlobalGPU method; };
layout(binding = LG_TEX_POSITION) uniform sampler2D texel_position;
layout(binding = LG_TEX_NORMAL_RATIO) uniform sampler2D texel_normal_ratio;
layout(rgba32f, binding = LUCENT_IMAGE_LG_ILLUMINATION) uniform writeonly image2D illumination;

void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(t, ivec2(method.counts.x)))) return;
  vec4 p = texelFetch(texel_position, t, 0);
  vec4 nr = texelFetch(texel_normal_ratio, t, 0);
  vec3 E = vec3(0.0f);
  if (p.w > 0.5f && nr.w > 0.0f) {
    ObjectGPU object = objects[int(p.w) - 1];
    float eta = materials[object.info.x].sigma_a.w;
    E = transmitted_irradiance(p.xyz, normalize(nr.xyz), eta);
  }
  imageStore(illumination, t, vec4(E, 0.0f));
}
