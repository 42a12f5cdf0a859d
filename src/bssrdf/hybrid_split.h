// hybrid_split.h: the split of the radial diffusion profile R_d(r) into a local and a global term (Chang et al.
// 2008, Section 4), C++ and GLSL: R_d = R_d W_l + R_d W_g with W_g = 1 - W_l, the split radius R_p from the
// importance function R_d^Imp(r) = 2 pi r R_d(r) and a threshold c, and the local term's circular pattern of
// L C + 1 points (the centre and L rings of C points) with radii by importance sampling of 2 pi r R_d W_l
// (Mertens et al. 2003). Lengths in the material's units (scene units on the GPU), K and c in their inverse.
#ifndef LUCENT_BSSRDF_HYBRID_SPLIT_H
#define LUCENT_BSSRDF_HYBRID_SPLIT_H
#include "shared/bridge.h"
#include "bssrdf/model.h"

#define LUCENT_HYBRID_GRID 1024  // radial steps of the tabulations below

LUCENT_SHADER_BEGIN

// W_l(r) (Section 4.1): 1/2 at r = R_p, falling as 0.5 e^{-(r - R_p) K} beyond and rising as
// 1 - 0.5 e^{(r - R_p) K} toward r = 0. The paper prints the inner branch as 1 - 0.5 e^{-(r - R_p) K}, which is
// negative for r < R_p - ln 2 / K; the sign here makes W_l continuous, in [0, 1] and 1/2 at R_p as its Fig. 3 shows.
LUCENT_INLINE float hybrid_local_weight(float r, float Rp, float K) {
  return r <= Rp ? 1.0f - 0.5f * exp((r - Rp) * K) : 0.5f * exp(-(r - Rp) * K);
}

LUCENT_INLINE float hybrid_global_weight(float r, float Rp, float K) { return 1.0f - hybrid_local_weight(r, Rp, K); }

// R_d^Imp(r) = 2 pi r R_d(r) [1/length]: R_d's share of the total diffuse reflectance per unit radius.
LUCENT_INLINE float hybrid_importance(int model, BandMedium m, float eta, float r) {
  return 2.0f * kPi * r * bssrdf_radial_Rd(model, m, eta, r);
}

// R_p of one band: the largest r in (0, r_max] with R_d^Imp(r) >= c (a grid of LUCENT_HYBRID_GRID steps from
// r_max down, then bisection); 0 when R_d^Imp stays below c.
LUCENT_INLINE float hybrid_band_Rp(int model, BandMedium m, float eta, float c, float r_max) {
  float dr = r_max / float(LUCENT_HYBRID_GRID);
  for (int k = LUCENT_HYBRID_GRID; k >= 1; --k) {
    float r = dr * float(k);
    if (hybrid_importance(model, m, eta, r) < c) continue;
    float lo = r, hi = r + dr;  // importance(lo) >= c > importance(hi) (or hi beyond the range)
    for (int i = 0; i < 24; ++i) {
      float mid = 0.5f * (lo + hi);
      if (hybrid_importance(model, m, eta, mid) >= c) lo = mid;
      else hi = mid;
    }
    return lo;
  }
  return 0.0f;
}

// How far the local term reaches: W_l < 0.5 e^{-20} beyond.
LUCENT_INLINE float hybrid_local_extent(float Rp, float K) { return Rp + 20.0f / K; }

// One stratum of the local pattern: `ring` 0 is the centre x_o, ring j >= 1 the j-th of L rings of C points. The
// band-mean local importance mean_b 2 pi r R_d,b W_l is split along r into L C + 1 equal shares: the centre the
// first, ring j the next C. Returns xyz: per band the integral of 2 pi r R_d W_l over the stratum (the estimator's
// weight of the stratum's mean irradiance), w: the ring's radius (the median of its share; 0 for the centre).
LUCENT_INLINE vec4 hybrid_ring(int model, BandMedium m0, BandMedium m1, BandMedium m2, float eta, float Rp, float K,
                               int ring, int L, int C) {
  float dr = hybrid_local_extent(Rp, K) / float(LUCENT_HYBRID_GRID);
  float total = 0.0f;
  for (int k = 0; k < LUCENT_HYBRID_GRID; ++k) {
    float r = (float(k) + 0.5f) * dr;
    float w = hybrid_local_weight(r, Rp, K);
    total += w * (hybrid_importance(model, m0, eta, r) + hybrid_importance(model, m1, eta, r) +
                  hybrid_importance(model, m2, eta, r));
  }
  float S = float(L * C + 1);
  float lo = ring == 0 ? 0.0f : (1.0f + float((ring - 1) * C)) / S;
  float hi = ring == L ? 2.0f : (1.0f + float(ring * C)) / S;
  float mid = ring == 0 ? -1.0f : 0.5f * (lo + min(hi, 1.0f));
  vec4 out_ring = vec4(0.0f);
  float cumulative = 0.0f;
  for (int k = 0; k < LUCENT_HYBRID_GRID && total > 0.0f; ++k) {
    float r = (float(k) + 0.5f) * dr;
    float w = hybrid_local_weight(r, Rp, K);
    vec3 f = w * vec3(hybrid_importance(model, m0, eta, r), hybrid_importance(model, m1, eta, r),
                      hybrid_importance(model, m2, eta, r));
    float share = (f.x + f.y + f.z) / total;
    float overlap = max(min(cumulative + share, hi) - max(cumulative, lo), 0.0f);
    if (share > 0.0f) out_ring += vec4(f * dr * (overlap / share), 0.0f);
    if (mid >= cumulative && mid < cumulative + share) out_ring.w = (float(k) + (mid - cumulative) / share) * dr;
    cumulative += share;
  }
  return out_ring;
}

LUCENT_SHADER_END

#endif
