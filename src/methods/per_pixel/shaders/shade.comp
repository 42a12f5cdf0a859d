// shade.comp: the caching-free baseline "per-pixel": for every camera pixel on a translucent object, the
// scattered radiosity of eq. 9 is estimated directly with N samples per band drawn in light space (the same
// estimator the radiosity maps use per map texel, common/light_sampling.glsl), as in translucent shadow maps.
// The estimate is view dependent, so it accumulates only while nothing, camera included, changes.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "common/light_sampling.glsl"
#include "methods/per_pixel/per_pixel_io.h"
#include "common/camera_pixel.glsl"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { PerPixelGPU method; };
layout(rgba32f, binding = LUCENT_IMAGE_PER_PIXEL_SUM) uniform image2D accumulated;  // rgb: sum of B, a: frames

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  vec4 sum = frame.seeds.z != 0u ? vec4(0.0f) : imageLoad(accumulated, pixel);
  uint point = uint(pixel.y * frame.output_size.x + pixel.x);
  sum += vec4(scattered_radiosity(object_index, x, n, camera_uv(pixel), point, 0u, method.counts.x), 1.0f);
  imageStore(accumulated, pixel, sum);
  return vec4(fresnel_transmittance(material.sigma_a.w, dot(n, w_o)) * kInvPi * sum.rgb / sum.a, 1.0f);
}
