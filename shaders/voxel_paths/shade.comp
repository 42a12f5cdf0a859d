// shade.comp: voxel-paths final pass: at every camera pixel on a translucent object, the radiance leaving the
// surface is F_t(eta, cos theta_o) exp(-n) / pi (paper eq. 1, with exp(-n) read as the radiosity reaching the
// point and spread over the hemisphere as by a Lambertian exit), exp(-n) interpolated trilinearly from the
// radiance 3D texture at the surface point; plus the lights' GGX reflection. Opaque objects are shaded directly.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "common/direct_shading.glsl"
#include "bssrdf/fresnel.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(binding = LUCENT_TEX_CAMERA_POSITION) uniform sampler2D camera_position;
layout(binding = LUCENT_TEX_CAMERA_NORMAL) uniform sampler2D camera_normal;
layout(binding = LUCENT_TEX_RADIOSITY) uniform sampler3D radiance;
layout(rgba32f, binding = LUCENT_IMAGE_HDR) uniform writeonly image2D hdr;
layout(std430, binding = LUCENT_BINDING_COUNTERS) buffer CounterBlock { CountersGPU counters; };

uniform vec3 u_origin;       // corner of voxel (0, 0, 0) [scene units]
uniform float u_grid_size;   // R h [scene units]

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.sizes.z || pixel.y >= frame.sizes.w) return;
  vec4 p = texelFetch(camera_position, pixel, 0);
  if (p.w < 0.5f) {
    imageStore(hdr, pixel, vec4(miss_radiance(pixel), 0.0f));
    return;
  }
  ObjectGPU object = objects[int(p.w) - 1];
  vec3 n = normalize(texelFetch(camera_normal, pixel, 0).xyz);
  vec3 w_o = normalize(frame.camera_position.xyz - p.xyz);
  vec3 L;
  if (object.info.x < 0) {
    if (dot(n, w_o) < 0.0f) n = -n;
    L = lambertian_direct(p.xyz, n, object.albedo.rgb);
  } else {
    atomicAdd(counters.translucent_pixels, 1u);
    atomicAdd(counters.covered_pixels, 1u);
    float eta = materials[object.info.x].sigma_a.w;
    vec3 E = textureLod(radiance, (p.xyz - u_origin) / u_grid_size, 0.0f).rgb;
    L = fresnel_transmittance(eta, dot(n, w_o)) * kInvPi * E + specular_direct(p.xyz, n, w_o, eta) +
        environment_specular(n, w_o, eta);
  }
  imageStore(hdr, pixel, vec4(L, 1.0f));
}
