// shade.comp: the screen-space method's final pass: the blurred transmitted irradiance leaves through the boundary,
// L = F_t(eta, n.w_o) albedo (E_blurred + E_back) / pi, albedo the material's total diffuse reflectance with the exit
// normalisation (bssrdf/diffuse_albedo.h), so a flat, uniformly lit slab shows what the standard dipole gives.
// E_back, the light crossing thin parts from behind (transmittance.glsl), when the method's transmittance is on; it
// is not blurred: T(d) is already the profile integrated over the back surface.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "bssrdf/diffuse_albedo.h"
#include "methods/screen_space/screen_space_io.h"
#include "methods/screen_space/shaders/transmittance.glsl"
#include "common/camera_pixel.glsl"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { ScreenSpaceGPU method; };
layout(rgba32f, binding = LUCENT_IMAGE_SCREEN_SPACE_BLURRED) uniform readonly image2D blurred;

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  float eta = material.sigma_a.w;
  vec3 albedo = diffuse_albedo(material.sigma_a.xyz, material.sigma_s.xyz, material.g.xyz, eta);
  vec4 E = imageLoad(blurred, pixel);
  if (method.counts.z != 0) E.rgb += back_irradiance(object_index, x, n, material, method.counts.y);
  return vec4(fresnel_transmittance(eta, dot(n, w_o)) * kInvPi * albedo * E.rgb, E.a);
}
