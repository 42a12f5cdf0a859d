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

// Henyey-Greenstein phase function [1/sr] of the cosine between the old and new directions (g > 0: forward).
LUCENT_INLINE float hg_phase(float cos_theta, float g) {
  float denominator = 1.0f + g * g - 2.0f * g * cos_theta;
  return (1.0f - g * g) / (4.0f * kWalkPi * denominator * sqrt(max(denominator, 1e-12f)));
}
LUCENT_INLINE vec3 hg_phase_bands(float cos_theta, vec3 g) {
  return vec3(hg_phase(cos_theta, g.x), hg_phase(cos_theta, g.y), hg_phase(cos_theta, g.z));
}

// A new direction after Henyey-Greenstein scattering of `direction` (unit) from two uniforms.
LUCENT_INLINE vec3 sample_hg(vec3 direction, float g, float u1, float u2) {
  float cos_theta = 1.0f - 2.0f * u1;
  if (abs(g) >= 1e-4f) {
    float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u1);
    cos_theta = (1.0f + g * g - s * s) / (2.0f * g);
  }
  cos_theta = clamp(cos_theta, -1.0f, 1.0f);
  float sin_theta = sqrt(max(0.0f, 1.0f - cos_theta * cos_theta));
  float phi = 2.0f * kWalkPi * u2;
  return normalize(walk_frame(direction) * vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta));
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
