// test_hybrid_cpu.cpp: the shared C++/GLSL split of bssrdf/hybrid_split.h on the CPU (the hybrid method, Chang et
// al. 2008, Section 4): W_l + W_g = 1, W_l continuous, in [0, 1] and 1/2 at R_p; R_p is the largest crossing of
// 2 pi r R_d(r) with c; the local pattern's strata carry the whole local integral 2 pi int r R_d W_l dr, their
// radii increase inside the local extent, and local + global integrals give the model's total R_d.
#include <cmath>

#include <gtest/gtest.h>

#include "bssrdf/hybrid_split.h"
#include "bssrdf/model.h"

namespace lucent::shader {
namespace {

constexpr int kDirectional = LUCENT_MODEL_DIRECTIONAL_DIPOLE;

BandMedium band(float sigma_a, float sigma_s) { return make_band_medium(sigma_a, sigma_s, 0.0f); }

// 2 pi int_0^r_max r R_d(r) w(r) dr by the midpoint rule on a fine grid.
template <class Weight>
double radial_integral(int model, BandMedium m, float eta, float r_max, Weight w) {
  const int n = 200000;
  const double dr = r_max / n;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const float r = static_cast<float>((k + 0.5) * dr);
    sum += static_cast<double>(hybrid_importance(model, m, eta, r)) * static_cast<double>(w(r)) * dr;
  }
  return sum;
}

TEST(HybridSplit, WeightsSumToOneAndAreContinuousAtRp) {
  for (float Rp : {0.0f, 0.5f, 2.4141f, 10.0f})
    for (float K : {0.3f, 1.5f, 6.0f}) {
      EXPECT_NEAR(hybrid_local_weight(Rp, Rp, K), 0.5f, 1e-6f);
      EXPECT_NEAR(hybrid_local_weight(Rp + 1e-4f, Rp, K), 0.5f, 1e-3f);
      EXPECT_NEAR(hybrid_local_weight(std::max(Rp - 1e-4f, 0.0f), Rp, K), 0.5f, Rp > 0.0f ? 1e-3f : 1e-6f);
      for (float r = 0.0f; r < Rp + 20.0f; r += 0.05f) {
        const float wl = hybrid_local_weight(r, Rp, K);
        EXPECT_GE(wl, 0.0f);
        EXPECT_LE(wl, 1.0f);
        EXPECT_NEAR(wl + hybrid_global_weight(r, Rp, K), 1.0f, 1e-6f);
        if (r > 0.0f) {
          EXPECT_LE(wl, hybrid_local_weight(r - 0.05f, Rp, K) + 1e-6f) << "W_l rises at r = " << r;
        }
      }
    }
}

TEST(HybridSplit, SplitRadiusIsTheLargestCrossingOfTheImportance) {
  // Skim milk (red band) of the paper's Fig. 3: sigma_a 0.0024, sigma_s' 0.70 mm^-1, eta 1.3.
  const BandMedium m = band(0.0024f, 0.70f);
  for (float c : {0.01f, 0.05f, 0.2f}) {
    const float r_max = 16.0f / m.sigma_tr;
    const float Rp = hybrid_band_Rp(kDirectional, m, 1.3f, c, r_max);
    ASSERT_GT(Rp, 0.0f) << c;
    EXPECT_NEAR(hybrid_importance(kDirectional, m, 1.3f, Rp), c, 1e-3f * c + 1e-6f) << c;
    for (float r = Rp * 1.001f + 1e-4f; r < r_max; r += r_max / 2000.0f)
      ASSERT_LT(hybrid_importance(kDirectional, m, 1.3f, r), c) << "c = " << c << ", r = " << r;
  }
  EXPECT_EQ(hybrid_band_Rp(kDirectional, m, 1.3f, 1e6f, 100.0f), 0.0f);  // never reaches c
}

TEST(HybridSplit, PatternStrataCarryTheLocalIntegral) {
  const BandMedium m0 = band(0.05f, 2.0f), m1 = band(0.08f, 2.2f), m2 = band(0.12f, 2.5f);
  for (int model : {LUCENT_MODEL_STANDARD_DIPOLE, kDirectional}) {
    const float Rp = 1.2f, K = 1.5f;
    for (int L : {1, 8, 20}) {
      const int C = 20;
      vec4 sum(0.0f);
      float previous = -1.0f;
      for (int ring = 0; ring <= L; ++ring) {
        const vec4 s = hybrid_ring(model, m0, m1, m2, 1.3f, Rp, K, ring, L, C);
        sum += vec4(vec3(s), 0.0f);
        EXPECT_GT(s.x, 0.0f);
        EXPECT_GT(s.w, previous) << "ring radii increase";
        EXPECT_LT(s.w, hybrid_local_extent(Rp, K));
        previous = s.w;
        if (ring > 0) {  // each ring holds C / (L C + 1) of the band-mean local integral
          const double share = (s.x + s.y + s.z) / 3.0;
          const vec4 centre = hybrid_ring(model, m0, m1, m2, 1.3f, Rp, K, 0, L, C);
          EXPECT_NEAR(share, (centre.x + centre.y + centre.z) / 3.0 * C, 2e-2 * share) << ring;
        }
      }
      const BandMedium bands[3] = {m0, m1, m2};
      const float extent = hybrid_local_extent(Rp, K);
      for (int b = 0; b < 3; ++b) {
        const double local = radial_integral(model, bands[b], 1.3f, extent, [&](float r) { return hybrid_local_weight(r, Rp, K); });
        EXPECT_NEAR(sum[b], local, 2e-3 * local) << "model " << model << " L " << L << " band " << b;
        const double global = radial_integral(model, bands[b], 1.3f, 60.0f, [&](float r) { return hybrid_global_weight(r, Rp, K); });
        const double whole = radial_integral(model, bands[b], 1.3f, 60.0f, [](float) { return 1.0f; });
        EXPECT_NEAR(local + global, whole, 2e-3 * whole);
      }
    }
  }
}

}  // namespace
}  // namespace lucent::shader
