// denoise.glsl: what the denoising stage's passes share: its block, the camera G-buffer, and the albedo each pixel's
// radiance is divided by before filtering (so that the filter smooths lighting, not the surface's colour).
#include "common/frame.glsl"
#include "bssrdf/diffuse_albedo.h"
#include "denoise/denoise_io.h"
#include "media/material_map.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std140, binding = LUCENT_BINDING_DENOISE) uniform DenoiseBlock { DenoiseGPU denoise; };
layout(binding = LUCENT_TEX_CAMERA_POSITION) uniform sampler2D camera_position;
layout(binding = LUCENT_TEX_CAMERA_NORMAL) uniform sampler2D camera_normal;

// The object a pixel sees (index + 1; 0: none, the background).
int pixel_object(vec4 position) { return int(position.w + 0.5f); }

float luminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

#if defined(LUCENT_MATERIAL_MAPS)
layout(binding = LUCENT_TEX_CAMERA_UV) uniform sampler2D camera_uv;
#endif

// The albedo the radiance is divided by: an opaque object's diffuse albedo; a translucent one's the diffuse albedo
// of its medium (bssrdf/diffuse_albedo.h: the emergent fraction on a flat, uniformly lit surface), per band, from
// its albedo map at the pixel where it has one (the map's single-scattering albedo sigma_s / sigma_t: only the
// ratio matters), so that the filter does not blur the texture. Kept above 1e-3 so that division and
// multiplication stay exact inverses of each other.
vec3 demodulation_albedo(int object, ivec2 pixel) {
  ObjectGPU o = objects[object - 1];
  vec3 albedo = o.albedo.rgb;
  if (o.info.x >= 0) {
    MaterialGPU m = materials[o.info.x];
    vec3 sigma_a = m.sigma_a.xyz, sigma_s = m.sigma_s.xyz;
#if defined(LUCENT_MATERIAL_MAPS)
    if (m.alpha_map.x >= 0) {
      sigma_s = clamp(material_map_value(m.alpha_map, texelFetch(camera_uv, pixel, 0).xy), vec3(0.0f), vec3(1.0f));
      sigma_a = vec3(1.0f) - sigma_s;
    }
#endif
    albedo = diffuse_albedo(sigma_a, sigma_s, m.g.xyz, m.sigma_a.w);
  }
  return max(albedo, vec3(1e-3f));
}

// The geometric weight of neighbour q for pixel p: zero on another object, the normals' agreement to a power, and
// the distance of q from p's tangent plane against the pixel's footprint times the offset in pixels.
float geometry_weight(vec4 p, vec3 n_p, vec4 q, vec3 n_q, float offset_pixels) {
  if (pixel_object(q) != pixel_object(p)) return 0.0f;
  float w_normal = pow(max(dot(n_p, n_q), 0.0f), denoise.weights.y);
  float footprint = length(p.xyz - frame.camera_position.xyz) * denoise.weights.w;
  float plane = abs(dot(n_p, q.xyz - p.xyz)) / max(denoise.weights.z * footprint * offset_pixels, 1e-30f);
  return w_normal * exp(-plane);
}
