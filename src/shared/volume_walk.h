// volume_walk.h: the steps of a volumetric random walk written once for C++ and GLSL (bridge.h): free-flight
// distances, Henyey-Greenstein phase sampling, reflection and refraction at a smooth dielectric boundary. The GPU
// path tracer (the random-walk method) runs them in float; the sphere-jump tables are generated with them on both
// sides. (Light through the boundary: shared/specular_chain.h.)
#ifndef LUCENT_SHARED_VOLUME_WALK_H
#define LUCENT_SHARED_VOLUME_WALK_H
#include "shared/bridge.h"

LUCENT_SHADER_BEGIN

LUCENT_CONST float kWalkPi = 3.14159265358979f;

// Distance to the next interaction, exponential with rate sigma_t, from a uniform u in (0, 1).
LUCENT_INLINE float free_flight(float sigma_t, float u) { return -log(u) / sigma_t; }

// An orthonormal frame (columns u, v, w) around unit w (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited").
LUCENT_INLINE mat3 walk_frame(vec3 w) {
  float s = w.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (s + w.z), b = w.x * w.y * a;
  return mat3(vec3(1.0f + s * w.x * w.x * a, s * b, -s * w.x), vec3(b, s + w.y * w.y * a, -w.y), w);
}

// Henyey-Greenstein phase function [1/sr] (g > 0: forward) from 1 - cos theta and 1 + cos theta, the cosine between
// the old and new directions. Exact to float over all of g in (-1, 1): the denominator 1 + g^2 - 2 g cos theta is
// written as (1 - g)^2 + 2 g (1 - cos theta) for g >= 0 and (1 + g)^2 - 2 g (1 + cos theta) for g < 0, sums of
// non-negative terms (the textbook form cancels to nothing near the peak once |g| > 0.999: its true value there,
// (1 - |g|)^2, is below float's resolution at 2), and 1 - g^2 as (1 - g)(1 + g).
LUCENT_INLINE float hg_phase_sides(float one_minus_cos, float one_plus_cos, float g) {
  float denominator = g >= 0.0f ? (1.0f - g) * (1.0f - g) + 2.0f * g * one_minus_cos
                                : (1.0f + g) * (1.0f + g) - 2.0f * g * one_plus_cos;
  denominator = max(denominator, 1e-30f);
  return (1.0f - g) * (1.0f + g) / (4.0f * kWalkPi * denominator * sqrt(denominator));
}
LUCENT_INLINE float hg_phase(float cos_theta, float g) { return hg_phase_sides(1.0f - cos_theta, 1.0f + cos_theta, g); }

// The phase function between unit directions a and b (cos theta = a.b): 1 -+ cos theta from |a -+ b|^2 / 2, which
// keep the angles below float's resolution of a dot product near 1 (a peak of width 1 - |g| = 1e-6 is one).
LUCENT_INLINE vec3 hg_phase_between(vec3 a, vec3 b, vec3 g) {
  vec3 d = a - b, s = a + b;
  float one_minus_cos = 0.5f * dot(d, d), one_plus_cos = 0.5f * dot(s, s);
  return vec3(hg_phase_sides(one_minus_cos, one_plus_cos, g.x), hg_phase_sides(one_minus_cos, one_plus_cos, g.y),
              hg_phase_sides(one_minus_cos, one_plus_cos, g.z));
}

// A new direction after Henyey-Greenstein scattering of `direction` (unit) from two uniforms. The inverse of the
// CDF is taken as x = 1 - cos theta about the peak (`direction` for g >= 0, its opposite for g < 0, sampled with |g|
// and 1 - u1 so that u1 maps to cos theta as the textbook inverse does): with e = 1 - |g|, t = e (1 + |g|) / (e +
// 2 |g| u), x = e (1 - u) (t + e) / (e + 2 |g| u), a product of positive terms, so a deflection of 1e-6 radians keeps
// its size (the textbook (1 + g^2 - t^2) / 2g cancels to float's resolution near the peak).
LUCENT_INLINE vec3 sample_hg(vec3 direction, float g, float u1, float u2) {
  float x = 2.0f * u1;  // isotropic
  vec3 peak = direction;
  if (abs(g) >= 1e-4f) {
    float a = abs(g), u = g >= 0.0f ? u1 : 1.0f - u1, e = 1.0f - a;
    float denominator = e + 2.0f * a * u;
    float t = e * (1.0f + a) / denominator;
    x = e * (1.0f - u) * (t + e) / denominator;
    if (g < 0.0f) peak = -direction;
  }
  x = clamp(x, 0.0f, 2.0f);
  float cos_theta = 1.0f - x, sin_theta = sqrt(x * (2.0f - x));
  float phi = 2.0f * kWalkPi * u2;
  return normalize(walk_frame(peak) * vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta));
}

// A cosine-distributed direction about unit n from two uniforms (Lambertian reflection).
LUCENT_INLINE vec3 sample_cosine(vec3 n, float u1, float u2) {
  float r = sqrt(u1), phi = 2.0f * kWalkPi * u2;
  return walk_frame(n) * vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0f, 1.0f - r * r)));
}

LUCENT_INLINE vec3 mirror_direction(vec3 direction, vec3 normal) {
  return direction - 2.0f * dot(direction, normal) * normal;
}

// The direction refracted into the side of relative index eta_ratio = n_other_side / n_this_side; `normal` of
// either orientation. Requires no total internal reflection.
LUCENT_INLINE vec3 refract_direction(vec3 direction, vec3 normal, float eta_ratio) {
  vec3 n = dot(direction, normal) < 0.0f ? normal : -normal;
  float cos_i = -dot(direction, n);
  float sin2_t = (1.0f - cos_i * cos_i) / (eta_ratio * eta_ratio);
  float cos_t = sqrt(max(0.0f, 1.0f - sin2_t));
  return normalize(direction / eta_ratio + (cos_i / eta_ratio - cos_t) * n);
}

LUCENT_SHADER_END

#endif  // LUCENT_SHARED_VOLUME_WALK_H
