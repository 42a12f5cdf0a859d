// heterogeneous_field.h: heterogeneous translucent media, shared by the voxel-paths method and the
// volumetric path tracer: a density multiplier m(x) >= 0 of a material over its object, in world space over the
// object's world-space bounds. The medium at x:
//   sigma_t(x) = m sigma_t,   sigma_s(x) = min(m, 1) sigma_s,   so   sigma_a(x) = m sigma_a + max(m - 1, 0) sigma_s
// so m < 1 thins the medium at constant albedo and m > 1 adds absorbing matter (the albedo falls as 1 / m where
// the medium is denser: dark marble veins). sigma_a(x) is evaluated in the last form, a sum of non-negative terms:
// m sigma_t - min(m, 1) sigma_s cancels to a few digits for high-albedo media (marble: sigma_a / sigma_t ~ 1e-3),
// so one rounding difference of a fused multiply-add between CPU and GPU would change it by ~1e-4. Fields (deterministic, no state):
//   none    m = 1.
//   marble  thin veins: a phase that advances one unit per `scale` along a fixed direction, warped by 4 octaves of
//           value noise (own integer-hash lattice, smoothstep interpolation); vein(x) = 1 - smoothstep(0, w, d),
//           d = |fract(phase) - 1/2| the distance to the nearest vein centre in periods, w = kMarbleVeinWidth;
//           m = 1 + contrast vein. vein >= 1/2 on a fraction w of a volume (phase uniform modulo 1).
//   layered a skin-like profile by depth below the surface of the object's bounding ellipsoid (exact for a
//           sphere): t = depth / scale; t < 1 dense outer layer (m = 1 + contrast), 1 <= t < 3 soft middle (m = 1),
//           t >= 3 denser core (m = 1 + contrast / 2).
//   volume  a grid of m values loaded from a file (lucent/material.h, MediumVolume), spanning the bounds;
//           trilinear between voxel centres, clamped at the border. The lookup is language-specific (a 3D texture
//           fetch in GLSL, MediumVolume::multiplier in C++); the weights are volume_trilinear_weights below.
// Compiled as C++ (namespace lucent::shader) and as GLSL.
#ifndef LUCENT_VOXEL_PATHS_HETEROGENEOUS_FIELD_H
#define LUCENT_VOXEL_PATHS_HETEROGENEOUS_FIELD_H
#include "shared/bridge.h"

LUCENT_SHADER_BEGIN

LUCENT_CONST int kFieldNone = 0;
LUCENT_CONST int kFieldMarble = 1;
LUCENT_CONST int kFieldLayered = 2;
LUCENT_CONST int kFieldVolume = 3;
LUCENT_CONST float kMarbleVeinWidth = 0.1f;  // half-width of a vein's smoothstep, in vein periods

// One translucent object's material, bounds and field (std430, per label; label 0 unused).
struct FieldMaterialGPU {
  vec4 sigma_a;  // rgb absorption [1/scene unit]; w: 1 = edge cost is sigma_tr, 0 = sigma_t
  vec4 sigma_s;  // rgb scattering (unreduced) [1/scene unit]
  vec4 g;        // rgb Henyey-Greenstein mean cosine
  vec4 lower;    // xyz: world-space bounds of the object [scene units]
  vec4 upper;
  vec4 field;    // x: kField*, y: feature size [scene units], z: contrast, w: unused
};

// Integer hash of a lattice point (xorshift-multiply mixing).
LUCENT_INLINE uint field_hash(int x, int y, int z) {
  uint h = uint(x) * 0x8DA6B343u + uint(y) * 0xD8163841u + uint(z) * 0xCB1AB31Fu + 0x68E31DA4u;
  h ^= h >> 16u;
  h *= 0x7FEB352Du;
  h ^= h >> 15u;
  h *= 0x846CA68Bu;
  h ^= h >> 16u;
  return h;
}

// Lattice value in [0, 1).
LUCENT_INLINE float field_lattice(ivec3 c) { return float(field_hash(c.x, c.y, c.z) >> 8u) * (1.0f / 16777216.0f); }

// Value noise in [0, 1): lattice values interpolated with smoothstep weights.
LUCENT_INLINE float field_value_noise(vec3 p) {
  vec3 f = floor(p);
  ivec3 c = ivec3(f);
  vec3 t = p - f;
  vec3 w = t * t * (3.0f - 2.0f * t);
  float x00 = mix(field_lattice(c), field_lattice(c + ivec3(1, 0, 0)), w.x);
  float x10 = mix(field_lattice(c + ivec3(0, 1, 0)), field_lattice(c + ivec3(1, 1, 0)), w.x);
  float x01 = mix(field_lattice(c + ivec3(0, 0, 1)), field_lattice(c + ivec3(1, 0, 1)), w.x);
  float x11 = mix(field_lattice(c + ivec3(0, 1, 1)), field_lattice(c + ivec3(1, 1, 1)), w.x);
  return mix(mix(x00, x10, w.y), mix(x01, x11, w.y), w.z);
}

// Four octaves (frequency x2, amplitude x1/2), in [0, 0.9375).
LUCENT_INLINE float field_turbulence(vec3 p) {
  float sum = 0.0f, amplitude = 0.5f;
  for (int octave = 0; octave < 4; ++octave) {
    sum += amplitude * field_value_noise(p);
    p = 2.0f * p + vec3(17.3f, 5.1f, 11.7f);
    amplitude *= 0.5f;
  }
  return sum;
}

// Marble vein weight in [0, 1] at p [scene units]; veins one `scale` apart.
LUCENT_INLINE float marble_vein(vec3 p, float scale) {
  vec3 q = p / scale;
  float phase = dot(q, vec3(0.87287156f, 0.43643578f, 0.21821789f)) + 4.0f * field_turbulence(q);
  float d = abs(fract(phase) - 0.5f);
  return 1.0f - smoothstep(0.0f, kMarbleVeinWidth, d);
}

// Depth of p below the surface of the ellipsoid inscribed in [lower, upper] [scene units], >= 0.
LUCENT_INLINE float ellipsoid_depth(vec3 p, vec3 lower, vec3 upper) {
  vec3 half_extent = max(0.5f * (upper - lower), vec3(1e-6f));
  float s = length((p - 0.5f * (lower + upper)) / half_extent);
  return max(0.0f, (1.0f - s) * min(half_extent.x, min(half_extent.y, half_extent.z)));
}

// The layered profile's multiplier at depth t = depth / scale.
LUCENT_INLINE float layered_multiplier(float t, float contrast) {
  if (t < 1.0f) return 1.0f + contrast;
  if (t < 3.0f) return 1.0f;
  return 1.0f + 0.5f * contrast;
}

// m(p) of the procedural fields (kFieldNone, kFieldMarble, kFieldLayered); kFieldVolume is looked up by the caller.
LUCENT_INLINE float field_multiplier(int field, vec3 p, vec3 lower, vec3 upper, float scale, float contrast) {
  if (field == kFieldMarble) return 1.0f + contrast * marble_vein(p, scale);
  if (field == kFieldLayered) return layered_multiplier(ellipsoid_depth(p, lower, upper) / scale, contrast);
  return 1.0f;
}

// Trilinear lookup in a grid of `size` values spanning [lower, upper] (values at voxel centres, clamped at the
// border): the continuous grid coordinate of p, the lower corner voxel of its cell (the upper neighbours are
// corner + 1, clamped to size - 1 by the caller) and the weights of the upper neighbours, u - corner.
LUCENT_INLINE vec3 volume_grid_coordinate(vec3 p, vec3 lower, vec3 upper, ivec3 size) {
  vec3 u = (p - lower) / max(upper - lower, vec3(1e-12f)) * vec3(size) - 0.5f;
  return clamp(u, vec3(0.0f), vec3(size - ivec3(1)));
}
LUCENT_INLINE ivec3 volume_corner(vec3 u, ivec3 size) { return max(min(ivec3(floor(u)), size - ivec3(2)), ivec3(0)); }

// The medium at a point where the field is m (see the top of this file).
LUCENT_INLINE vec3 field_sigma_s(FieldMaterialGPU material, float m) { return min(m, 1.0f) * vec3(material.sigma_s); }
LUCENT_INLINE vec3 field_sigma_a(FieldMaterialGPU material, float m) {
  return m * vec3(material.sigma_a) + max(m - 1.0f, 0.0f) * vec3(material.sigma_s);
}
LUCENT_INLINE vec3 field_sigma_t(FieldMaterialGPU material, float m) {
  return m * (vec3(material.sigma_a) + vec3(material.sigma_s));
}

// The edge-cost coefficient of a voxel of `material` where the field is m: sigma_t(x), or with the material's
// sigma_tr flag sqrt(3 sigma_a sigma_t') of the medium there.
LUCENT_INLINE vec3 field_coefficient(FieldMaterialGPU material, float m) {
  if (material.sigma_a.w < 0.5f) return field_sigma_t(material, m);
  vec3 sigma_a = field_sigma_a(material, m);
  return sqrt(3.0f * sigma_a * (sigma_a + field_sigma_s(material, m) * (1.0f - vec3(material.g))));
}

LUCENT_SHADER_END

#endif  // LUCENT_VOXEL_PATHS_HETEROGENEOUS_FIELD_H
