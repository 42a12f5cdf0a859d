// layer_parallax.h: depth parallax of an inner layer under an outer one (Oat 2006 as in Norberg 2010, Section
// 2.2.1), shared by C++ and GLSL. In tangent space (x along u, y along v, z out of the surface), with V the unit
// direction toward the viewer and N the outer layer's (normal-mapped) unit normal:
//   R = -V - 2 (-V . N) N        (Eq. 15: the view direction reflected about N)
//   T = (R_x, R_y, -R_z)         (Eq. 16: reflected again about the surface plane: the transmission vector)
//   s = d / |T_z|                (Eq. 17: distance along T to the inner layer, d below the outer one)
//   offset = s (T_x, T_y)        (Eq. 18: in the units of d, along the tangent and bi-normal)
// With N = (0, 0, 1), T = -V: the line of sight continues straight, as through an index-matched layer; a tilted N
// bends it, the thesis's "refraction" of the normal map. |T_z| is kept above `min_cos` so that grazing views do not
// push the offset toward infinity (the thesis instead fades the inner layer out with N . V, Eq. 19).
// Compiled as C++ (namespace lucent::shader) and as GLSL.
#ifndef LUCENT_MEDIA_LAYER_PARALLAX_H
#define LUCENT_MEDIA_LAYER_PARALLAX_H
#include "shared/bridge.h"

LUCENT_SHADER_BEGIN

LUCENT_INLINE vec3 parallax_transmission(vec3 view, vec3 normal) {
  vec3 r = -view - 2.0f * dot(-view, normal) * normal;
  return vec3(r.x, r.y, -r.z);
}

// xy: the offset (Eq. 18); z: the transmission distance s (Eq. 17), which also sets the inner layer's blur.
LUCENT_INLINE vec3 parallax_offset(vec3 transmission, float depth, float min_cos) {
  float s = depth / max(abs(transmission.z), min_cos);
  return vec3(s * transmission.x, s * transmission.y, s);
}

// The weight of the inner layer (Eq. 19 and Section 2.2.3): the outer layer's see-through weight times
// saturate(N . V).
LUCENT_INLINE float parallax_inner_weight(float see_through, vec3 normal, vec3 view) {
  return see_through * clamp(dot(normal, view), 0.0f, 1.0f);
}

LUCENT_SHADER_END

#endif  // LUCENT_MEDIA_LAYER_PARALLAX_H
