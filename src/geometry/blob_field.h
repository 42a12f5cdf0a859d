// blob_field.h: the implicit blob scene's scalar field, shared by C++ and GLSL.
//
// f(x, t) = sum_{i<4} exp(-|x - c_i(t)|^2 / (2 s_i^2)) - kBlobThreshold; the body is {f > 0} and its surface
// {f = 0}. Each centre c_i(t) runs on a closed Lissajous loop, c_i = o_i + a_i * sin(k_i * theta_i + phi_i)
// (componentwise, integer k_i), theta_i = 2 pi fract(t / P_i), so blob i repeats with period P_i; the four
// periods differ, the whole field repeats after their least common multiple. Units: positions in scene
// units, t in seconds.
//
// Bound: a point with f >= 0 has some Gaussian >= kBlobThreshold / 4, so it lies within
// s_i sqrt(2 ln(4 / kBlobThreshold)) of a centre; blob_body_bound() adds that to the loops' extents and is
// therefore a box the body never leaves (the extractor's default grid box is that box plus a margin).
#ifndef LUCENT_GEOMETRY_BLOB_FIELD_H
#define LUCENT_GEOMETRY_BLOB_FIELD_H
#include "shared/bridge.h"

#define LUCENT_BLOB_COUNT 4

LUCENT_SHADER_BEGIN

LUCENT_CONST float kBlobThreshold = 0.5f;
LUCENT_CONST float kBlobTwoPi = 6.28318530717959f;

// One blob: a Gaussian of width sigma whose centre runs on a Lissajous loop.
struct BlobPath {
  vec3 origin;     // loop centre o_i [scene units]
  vec3 amplitude;  // a_i [scene units]
  vec3 frequency;  // k_i, integers: cycles per period
  vec3 phase;      // phi_i [radians]
  float period;    // P_i [s]
  float sigma;     // s_i [scene units]
};

// The four loops: a pair on each side of x = 0 that drift toward and away from each other, so the body is
// one piece about half of the time and two pieces (about 1.1 units across each) the other half; the merged
// body is 1.7 to 2.3 units long. Periods 5, 7, 9 and 11 s.
LUCENT_INLINE BlobPath blob_path(int i) {
  BlobPath b;
  if (i == 0) {
    b.origin = vec3(-0.60f, 0.04f, 0.0f);
    b.amplitude = vec3(0.28f, 0.24f, 0.20f);
    b.frequency = vec3(1.0f, 2.0f, 1.0f);
    b.phase = vec3(0.0f, 0.5f, 1.5707963f);
    b.period = 5.0f;
    b.sigma = 0.288f;
  } else if (i == 1) {
    b.origin = vec3(-0.56f, -0.08f, 0.04f);
    b.amplitude = vec3(0.24f, 0.28f, 0.24f);
    b.frequency = vec3(1.0f, 1.0f, 2.0f);
    b.phase = vec3(1.0f, 0.0f, 0.3f);
    b.period = 7.0f;
    b.sigma = 0.264f;
  } else if (i == 2) {
    b.origin = vec3(0.60f, 0.0f, -0.04f);
    b.amplitude = vec3(0.28f, 0.20f, 0.28f);
    b.frequency = vec3(1.0f, 1.0f, 2.0f);
    b.phase = vec3(3.14159265f, 1.2f, 0.0f);
    b.period = 9.0f;
    b.sigma = 0.296f;
  } else {
    b.origin = vec3(0.56f, 0.08f, 0.0f);
    b.amplitude = vec3(0.24f, 0.24f, 0.24f);
    b.frequency = vec3(2.0f, 1.0f, 1.0f);
    b.phase = vec3(2.0f, 2.5f, 0.7f);
    b.period = 11.0f;
    b.sigma = 0.272f;
  }
  return b;
}

// c_i(t) [scene units].
LUCENT_INLINE vec3 blob_center(int i, float time) {
  BlobPath b = blob_path(i);
  float theta = kBlobTwoPi * fract(time / b.period);
  return b.origin + b.amplitude * sin(b.frequency * theta + b.phase);
}

// The four blobs at one time: what the field needs, computed once per frame (or per call).
struct BlobState {
  vec4 blobs[LUCENT_BLOB_COUNT];  // xyz: centre c_i(t) [scene units]; w: sigma s_i [scene units]
};

LUCENT_INLINE BlobState blob_state(float time) {
  BlobState state;
  for (int i = 0; i < LUCENT_BLOB_COUNT; ++i) state.blobs[i] = vec4(blob_center(i, time), blob_path(i).sigma);
  return state;
}

// f at x for the blobs of `state`: positive inside the body.
LUCENT_INLINE float blob_field_of(BlobState state, vec3 x) {
  float sum = 0.0f;
  for (int i = 0; i < LUCENT_BLOB_COUNT; ++i) {
    vec3 d = x - vec3(state.blobs[i]);
    float s = state.blobs[i].w;
    sum += exp(-dot(d, d) / (2.0f * s * s));
  }
  return sum - kBlobThreshold;
}

// grad f = sum_i -(x - c_i) / s_i^2 * exp(-|x - c_i|^2 / (2 s_i^2)) [1/scene unit].
LUCENT_INLINE vec3 blob_field_gradient_of(BlobState state, vec3 x) {
  vec3 gradient = vec3(0.0f);
  for (int i = 0; i < LUCENT_BLOB_COUNT; ++i) {
    vec3 d = x - vec3(state.blobs[i]);
    float s = state.blobs[i].w;
    gradient -= d * (exp(-dot(d, d) / (2.0f * s * s)) / (s * s));
  }
  return gradient;
}

// f(x, t) and its gradient.
LUCENT_INLINE float blob_field(vec3 x, float time) { return blob_field_of(blob_state(time), x); }
LUCENT_INLINE vec3 blob_field_gradient(vec3 x, float time) { return blob_field_gradient_of(blob_state(time), x); }

// Outward unit normal: toward decreasing f.
LUCENT_INLINE vec3 blob_outward_normal(vec3 x, float time) {
  return normalize(-blob_field_gradient(x, time));
}

// Half-extents of a box centred at the origin that contains the body at every time (see the header comment).
LUCENT_INLINE vec3 blob_body_bound() {
  vec3 bound = vec3(0.0f);
  for (int i = 0; i < LUCENT_BLOB_COUNT; ++i) {
    BlobPath b = blob_path(i);
    float reach = b.sigma * sqrt(2.0f * log(4.0f / kBlobThreshold));
    bound = max(bound, abs(b.origin) + abs(b.amplitude) + vec3(reach));
  }
  return bound;
}

LUCENT_SHADER_END

#endif
