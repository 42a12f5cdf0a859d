// point_light.h: point and spot lights, shared by C++ and the shaders: the spot cone's falloff and the
// stereographic sampling of a point light's G-buffer (Dal Corso et al. 2015, Section 3.3, Eqs. 13-14).
//
// Stereographic sampling. For a point x_o at distance R from the light x_l, samples x_j are drawn around x_o in
// the plane through x_o perpendicular to a = x_l - x_o (the analogue of a directional light's view plane).
// Eqs. 13-14 map x_j to the point x_stereo where the line from the pole P = x_l + a (the antipode of x_o on the
// sphere of radius R about the light) through x_j meets that sphere again; the G-buffer is looked up in the
// direction x_stereo - x_l. This is an inverse stereographic projection, so the whole sphere of directions is
// reachable from one plane (planar look-ups with x_j - x_l reach only a hemisphere, and poorly). Its Jacobian is
// known in closed form: dA_plane / d omega = R^2 (1 + rho^2 / (4 R^2))^2 with rho = |x_j - x_o|. Dividing a
// sample by p_plane(x_j) times this Jacobian makes the estimator of Eq. 9 unbiased for any surface the ray in
// that direction hits (the irradiance's cos theta_i / d^2 cancels against the solid angle to area conversion).
#ifndef LUCENT_LIGHTS_POINT_LIGHT_H
#define LUCENT_LIGHTS_POINT_LIGHT_H
#include "shared/bridge.h"

LUCENT_SHADER_BEGIN

// Spot cone: 1 inside the inner cone, 0 outside the outer one, smooth in between (cosines of half-angles).
LUCENT_INLINE float spot_falloff(float cos_angle, float cos_inner, float cos_outer) {
  if (cos_inner <= cos_outer) return cos_angle >= cos_outer ? 1.0f : 0.0f;
  float t = clamp((cos_angle - cos_outer) / (cos_inner - cos_outer), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

struct StereographicSample {
  vec3 direction;                      // unit direction from the light for the G-buffer look-up
  float plane_area_per_solid_angle;    // dA_plane / d omega at x_j [length^2 / sr]
};

// Eqs. 13-14: x_l the light, x_o the point whose radiosity is estimated, x_j = x_o + an offset perpendicular
// to x_l - x_o.
LUCENT_INLINE StereographicSample stereographic_sample(vec3 x_l, vec3 x_o, vec3 x_j) {
  vec3 a = x_l - x_o;
  vec3 ell = normalize((x_j - x_l) - a);              // Eq. 14
  vec3 stereo = a - 2.0f * dot(a, ell) * ell;         // Eq. 13: x_stereo - x_l
  float R2 = dot(a, a);
  vec3 offset = x_j - x_o;
  float q = 1.0f + dot(offset, offset) / (4.0f * R2);
  StereographicSample s;
  s.direction = normalize(stereo);
  s.plane_area_per_solid_angle = R2 * q * q;
  return s;
}

LUCENT_SHADER_END

#endif
