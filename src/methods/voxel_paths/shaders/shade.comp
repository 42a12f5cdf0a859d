// shade.comp: voxel-paths final pass: at every camera pixel on a translucent object, the radiance leaving the
// surface is F_t(eta, cos theta_o) exp(-n) / pi (paper eq. 1, with exp(-n) read as the radiosity reaching the
// point and spread over the hemisphere as by a Lambertian exit), exp(-n) interpolated trilinearly from the
// radiance 3D texture at the surface point. The rest of the pixel's shading is common/camera_pixel.glsl.
#include "common/frame.glsl"
#include "common/lights.glsl"
#include "common/camera_pixel.glsl"

layout(binding = VOXEL_TEXTURE_RADIANCE) uniform sampler3D radiance;

uniform vec3 u_origin;       // corner of voxel (0, 0, 0) [scene units]
uniform float u_grid_size;   // R h [scene units]

vec4 subsurface_radiance(ivec2 pixel, int object_index, vec3 x, vec3 n, vec3 w_o, MaterialGPU material) {
  vec3 E = textureLod(radiance, (x - u_origin) / u_grid_size, 0.0f).rgb;
  return vec4(fresnel_transmittance(material.sigma_a.w, dot(n, w_o)) * kInvPi * E, 1.0f);
}
