// shade.comp: the caching-free baseline "per-pixel": for every camera pixel on a translucent object, the
// scattered radiosity of eq. 9 is estimated directly with N samples per band drawn in light space (the same
// estimator the radiosity maps use per map texel, common/light_sampling.glsl), as in translucent shadow maps.
// The estimate is view dependent, so it accumulates only while nothing, camera included, changes.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "common/light_sampling.glsl"
#include "common/direct_shading.glsl"
#include "bssrdf/fresnel.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(binding = LUCENT_TEX_CAMERA_POSITION) uniform sampler2D camera_position;
layout(binding = LUCENT_TEX_CAMERA_NORMAL) uniform sampler2D camera_normal;
layout(rgba32f, binding = LUCENT_IMAGE_RADIOSITY) uniform image2D accumulated;  // rgb: sum of B, a: frames
layout(rgba32f, binding = LUCENT_IMAGE_HDR) uniform writeonly image2D hdr;
layout(std430, binding = LUCENT_BINDING_COUNTERS) buffer CounterBlock { CountersGPU counters; };

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.sizes.z || pixel.y >= frame.sizes.w) return;
  vec4 p = texelFetch(camera_position, pixel, 0);
  if (p.w < 0.5f) {
    imageStore(hdr, pixel, vec4(miss_radiance(pixel), 0.0f));
    return;
  }
  int object_index = int(p.w) - 1;
  ObjectGPU object = objects[object_index];
  vec3 n = normalize(texelFetch(camera_normal, pixel, 0).xyz);
  vec3 w_o = normalize(frame.camera_position.xyz - p.xyz);
  vec3 L;
  if (object.info.x < 0) {
    if (dot(n, w_o) < 0.0f) n = -n;
    L = lambertian_direct(p.xyz, n, object.albedo.rgb);
  } else {
    atomicAdd(counters.translucent_pixels, 1u);
    atomicAdd(counters.covered_pixels, 1u);
    vec4 sum = frame.seeds.z != 0u ? vec4(0.0f) : imageLoad(accumulated, pixel);
    sum += vec4(scattered_radiosity(object_index, p.xyz, n, uint(pixel.y * frame.sizes.z + pixel.x), 0u), 1.0f);
    imageStore(accumulated, pixel, sum);
    float eta = materials[object.info.x].sigma_a.w;
    L = fresnel_transmittance(eta, dot(n, w_o)) * kInvPi * sum.rgb / sum.a + specular_direct(p.xyz, n, w_o, eta) + environment_specular(n, w_o, eta);
  }
  imageStore(hdr, pixel, vec4(L, 1.0f));
}
