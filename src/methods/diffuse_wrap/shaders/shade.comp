// shade.comp: the diffuse-wrap baseline: every translucent pixel is shaded as a Lambertian surface with wrap
// lighting (common/diffuse_lighting.glsl) whose albedo is the material's total diffuse reflectance with the exit
// normalisation (bssrdf/diffuse_albedo.h): L = F_t(w_o) albedo E_t / pi. No light travels under the surface.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "common/diffuse_lighting.glsl"
#include "bssrdf/diffuse_albedo.h"
#include "methods/diffuse_wrap/diffuse_wrap_io.h"
#include "common/camera_pixel.glsl"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { DiffuseWrapGPU method; };

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  float eta = material.sigma_a.w;
  vec3 albedo = diffuse_albedo(material.sigma_a.xyz, material.sigma_s.xyz, material.g.xyz, eta);
  vec3 E_t = transmitted_irradiance(x, n, eta, method.shading.x, true);
  return vec4(fresnel_transmittance(eta, dot(n, w_o)) * kInvPi * albedo * E_t, 1.0f);
}
