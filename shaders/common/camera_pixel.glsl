// camera_pixel.glsl: the final per-pixel pass every method shares, as one main(): it reads the camera G-buffer,
// writes the background (or environment) where the camera ray missed, Lambertian direct light with shadows on
// opaque objects, and on translucent ones the method's subsurface radiance plus the GGX reflection of the lights
// and the environment's specular reflection; it counts the translucent pixels and those the method covers
// (CountersGPU). The including shader includes common/frame.glsl and common/lights.glsl first and defines
//
//   vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material);
//     rgb: radiance leaving x toward w_o by subsurface scattering; a: 1 when the method has data for x, else 0
//
// It may call camera_uv(pixel), the texture coordinates of x (0 unless the scene has textured materials).
//
// and, optionally before the include, LUCENT_OPAQUE_INDIRECT(x, n): irradiance an opaque surface receives from
// the translucent objects (emergent light), added to its Lambertian shading.
#include "common/direct_shading.glsl"

#ifndef LUCENT_OPAQUE_INDIRECT
#define LUCENT_OPAQUE_INDIRECT(x, n) vec3(0.0f)
#endif

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(binding = LUCENT_TEX_CAMERA_POSITION) uniform sampler2D camera_position;
layout(binding = LUCENT_TEX_CAMERA_NORMAL) uniform sampler2D camera_normal;
#if defined(LUCENT_MATERIAL_MAPS)
layout(binding = LUCENT_TEX_CAMERA_UV) uniform sampler2D camera_uv_texture;
vec2 camera_uv(ivec2 pixel) { return texelFetch(camera_uv_texture, pixel, 0).xy; }
#else
vec2 camera_uv(ivec2 pixel) { return vec2(0.0f); }
#endif
layout(rgba32f, binding = LUCENT_IMAGE_HDR) uniform writeonly image2D hdr;
layout(std430, binding = LUCENT_BINDING_COUNTERS) buffer CounterBlock { CountersGPU counters; };

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material);

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.output_size.x || pixel.y >= frame.output_size.y) return;
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
    if (dot(n, w_o) < 0.0f) n = -n;  // two-sided opaque surfaces (planes seen from below)
    L = object.albedo.rgb * kInvPi * (LUCENT_OPAQUE_INDIRECT(p.xyz, n)) + lambertian_direct(p.xyz, n, object.albedo.rgb);
  } else {
    MaterialGPU material = materials[object.info.x];
    float eta = material.sigma_a.w;
    vec4 sss = subsurface_radiance(pixel, object_index, p.xyz, n, w_o, material);
    atomicAdd(counters.translucent_pixels, 1u);
    if (sss.a > 0.0f) atomicAdd(counters.covered_pixels, 1u);
    L = sss.rgb + specular_direct(p.xyz, n, w_o, eta) + environment_specular(n, w_o, eta);
  }
  imageStore(hdr, pixel, vec4(L, 1.0f));
}
