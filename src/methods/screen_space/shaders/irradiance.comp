// irradiance.comp: the screen-space method's first pass: per camera pixel on a translucent object, the irradiance
// transmitted through its boundary, E_t = sum over lights of F_t(eta, n.l) (n.l) E V (common/diffuse_lighting.glsl
// with no wrap; shadows from the light G-buffer). Other pixels get 0 with a = 0.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "common/diffuse_lighting.glsl"
#include "methods/screen_space/screen_space_io.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(binding = LUCENT_TEX_CAMERA_POSITION) uniform sampler2D camera_position;
layout(binding = LUCENT_TEX_CAMERA_NORMAL) uniform sampler2D camera_normal;
layout(rgba32f, binding = LUCENT_IMAGE_SCREEN_SPACE_IRRADIANCE) uniform writeonly image2D irradiance;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.output_size.x || pixel.y >= frame.output_size.y) return;
  vec4 p = texelFetch(camera_position, pixel, 0);
  int material_index = p.w < 0.5f ? -1 : objects[int(p.w) - 1].info.x;
  if (material_index < 0) {
    imageStore(irradiance, pixel, vec4(0.0f));
    return;
  }
  vec3 n = normalize(texelFetch(camera_normal, pixel, 0).xyz);
  float eta = materials[material_index].sigma_a.w;
  imageStore(irradiance, pixel, vec4(transmitted_irradiance(p.xyz, n, eta, 0.0f, true), 1.0f));
}
