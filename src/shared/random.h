// random.h: counter-based random numbers shared by C++ and GLSL, so that any texel, pixel, sample and frame
// can be re-rendered alone and the CPU can reproduce a GPU sample sequence.
// Hash: PCG-RXS-M-XS 32 (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020).
#ifndef LUCENT_SHARED_RANDOM_H
#define LUCENT_SHARED_RANDOM_H
#include "shared/bridge.h"

LUCENT_SHADER_BEGIN

LUCENT_INLINE uint pcg_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Seed from up to four coordinates (for example seed, texel index, map, frame).
LUCENT_INLINE uint seed_from(uint a, uint b, uint c, uint d) {
  return pcg_hash(a ^ pcg_hash(b ^ pcg_hash(c ^ pcg_hash(d))));
}

// Advances the state and returns a float in the open interval (0, 1).
LUCENT_INLINE float next_float(uint state) {
  return (float(pcg_hash(state) >> 8u) + 0.5f) * (1.0f / 16777216.0f);
}

LUCENT_SHADER_END

#endif
