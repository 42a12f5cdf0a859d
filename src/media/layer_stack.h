// layer_stack.h: a stack of up to four layers under a surface, each of variable thickness (a heightfield, one
// channel of an RGBA texture: subsurface texture mapping, Francois et al. 2006 as presented by Norberg 2010,
// Section 2.1), and the pieces of its single-scattering estimate shared by C++ and GLSL:
//   - which layer a depth lies in, from the four thicknesses at a texture coordinate;
//   - the Schlick phase function (Norberg Eq. 3);
//   - the reduced intensity's transmittance through the layers above a point (Eqs. 12-14, with the max(..., 0)
//     of Section 3.1.1 so that layers the light never reaches contribute nothing).
// Depths and thicknesses are in scene units; the layer below the last one is empty (no medium).
// Compiled as C++ (namespace lucent::shader) and as GLSL.
#ifndef LUCENT_MEDIA_LAYER_STACK_H
#define LUCENT_MEDIA_LAYER_STACK_H
#include "shared/bridge.h"

LUCENT_SHADER_BEGIN

LUCENT_CONST int kMaxStackLayers = 4;
LUCENT_CONST float kStackPi = 3.14159265358979f;

// The Schlick approximation of the Henyey-Greenstein phase function with parameter k in (-1, 1):
// p = (1 - k^2) / (4 pi (1 - k cos)^2), cos between the directions of propagation before and after scattering
// (Norberg Eq. 3 writes 1 + g cos with the angle between the incident direction, pointing back toward the light,
// and the outgoing one: the same function). Normalised over the sphere for every k.
LUCENT_INLINE float schlick_phase(float k, float cos_theta) {
  float d = 1.0f - k * cos_theta;
  return (1.0f - k * k) / (4.0f * kStackPi * d * d);
}

// Schlick's k for a Henyey-Greenstein mean cosine g (Blasi et al. 1993): k = 1.55 g - 0.55 g^3. Eq. 3 of the
// thesis puts g itself in place of k, which gives a different mean cosine (k = 0.8 has g ~ 0.6).
LUCENT_INLINE float schlick_k_from_g(float g) { return 1.55f * g - 0.55f * g * g * g; }

// The layer holding depth z (>= 0) below the surface where the layers are `thickness` thick: 0-3, or
// kMaxStackLayers below the stack.
LUCENT_INLINE int stack_layer_at(vec4 thickness, float z) {
  float bottom = thickness.x;
  if (z < bottom) return 0;
  bottom += thickness.y;
  if (z < bottom) return 1;
  bottom += thickness.z;
  if (z < bottom) return 2;
  bottom += thickness.w;
  if (z < bottom) return 3;
  return kMaxStackLayers;
}

// Distance the light travels in layer i (Eq. 14 with the max(.., 0) fix): the light path of length km (|K'M|)
// crosses layers of thickness D_j at cos_theta to their planes, so it runs D_j / cos_theta in each layer it
// passes and what remains of km in the last.
LUCENT_INLINE float stack_light_distance(float km, float above, float thickness_i, float cos_theta) {
  return min(max(km - above / cos_theta, 0.0f), thickness_i / cos_theta);
}

// exp(-sum_i sigma_t,i d_i) (Eq. 12 for four layers): the fraction of the refracted light that reaches the end
// of a light path of length km through layers of thickness D (Eq. 13's average of the thicknesses at K' and M)
// at cos_theta. sigma_t0..3: rgb extinction of each layer [1/scene unit].
LUCENT_INLINE vec3 stack_light_transmittance(float km, vec4 D, float cos_theta, vec3 sigma_t0, vec3 sigma_t1,
                                             vec3 sigma_t2, vec3 sigma_t3) {
  float d0 = stack_light_distance(km, 0.0f, D.x, cos_theta);
  float d1 = stack_light_distance(km, D.x, D.y, cos_theta);
  float d2 = stack_light_distance(km, D.x + D.y, D.z, cos_theta);
  float d3 = stack_light_distance(km, D.x + D.y + D.z, D.w, cos_theta);
  return exp(-(sigma_t0 * d0 + sigma_t1 * d1 + sigma_t2 * d2 + sigma_t3 * d3));
}

LUCENT_SHADER_END

#endif  // LUCENT_MEDIA_LAYER_STACK_H
