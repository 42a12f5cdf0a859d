// denoise.glsl: what the denoising stage's passes share: its block, the camera G-buffer, and the albedo each pixel's
// radiance is divided by before filtering (so that the filter smooths lighting, not the surface's colour).
#include "common/frame.glsl"
#include "bssrdf/diffuse_albedo.h"
#include "denoise/denoise_io.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std140, binding = LUCENT_BINDING_DENOISE) uniform DenoiseBlock { DenoiseGPU denoise; };
layout(binding = LUCENT_TEX_CAMERA_POSITION) uniform sampler2D camera_position;
layout(binding = LUCENT_TEX_CAMERA_NORMAL) uniform sampler2D camera_normal;

// The object a pixel sees (index + 1; 0: none, the background).
int pixel_object(vec4 position) { return int(position.w + 0.5f); }

float luminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

// The albedo the radiance is divided by: an opaque object's diffuse albedo; a translucent one's the diffuse albedo
// of its medium (bssrdf/diffuse_albedo.h: the emergent fraction on a flat, uniformly lit surface), per band.
// Kept above 1e-3 so that division and multiplication stay exact inverses of each other.
vec3 demodulation_albedo(int object) {
  ObjectGPU o = objects[object - 1];
  vec3 albedo = o.albedo.rgb;
  if (o.info.x >= 0) {
    MaterialGPU m = materials[o.info.x];
    albedo = diffuse_albedo(m.sigma_a.xyz, m.sigma_s.xyz, m.g.xyz, m.sigma_a.w);
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
