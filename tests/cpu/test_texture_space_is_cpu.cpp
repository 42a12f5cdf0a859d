// test_texture_space_is_cpu.cpp: the shared C++/GLSL pieces of the texture-space-is method on the CPU: the
// radially symmetric R_d of bssrdf/model.h against the model values (the spec's directional dipole at normal
// incidence, the standard dipole's R_d and its closed-form total), and the top-down mipmap descent of
// shared/mip_sampling.h (chi-square of the sample histogram against p = E' / E'_total on a small image).
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "bssrdf/model.h"
#include "shared/mip_sampling.h"

namespace {

using namespace lucent::shader;

// The directional dipole at normal incidence on a plane, potato (eta 1.3), from shared/spec/bssrdf-models.md (as in
// test_bssrdf_models.cpp): R_d = pi S_d.
TEST(TextureSpaceIsRd, DirectionalDipoleRadialProfileIsPiTimesTheSpecValuesAtNormalIncidence) {
  const float sigma_a[3] = {0.0024f, 0.009f, 0.12f}, sigma_s[3] = {0.68f, 0.7f, 0.55f};
  struct Case {
    float r;
    double S_d[3];
  };
  const Case cases[] = {{0.1f, {8.019856e-02, 8.464636e-02, 7.343868e-02}},
                        {0.5f, {2.237964e-02, 2.280510e-02, 1.863656e-02}},
                        {1.0f, {9.567225e-03, 9.536976e-03, 6.863451e-03}},
                        {2.0f, {3.558839e-03, 3.410761e-03, 1.872209e-03}},
                        {4.0f, {1.114858e-03, 9.862984e-04, 3.082317e-04}},
                        {8.0f, {2.449902e-04, 1.806823e-04, 1.859256e-05}}};
  for (const Case& c : cases)
    for (int band = 0; band < 3; ++band) {
      const float R_d = bssrdf_radial_Rd(LUCENT_MODEL_DIRECTIONAL_DIPOLE,
                                         make_band_medium(sigma_a[band], sigma_s[band], 0.0f), 1.3f, c.r);
      EXPECT_NEAR(R_d, kPi * c.S_d[band], 2e-4 * kPi * c.S_d[band]) << "r " << c.r << " band " << band;
    }
}

TEST(TextureSpaceIsRd, StandardDipoleIsItsRdAndIntegratesToTheClosedFormTotal) {
  for (float alpha : {0.3f, 0.9f, 0.99f})
    for (float eta : {1.0f, 1.3f}) {
      const BandMedium m = make_band_medium(1.0f - alpha, alpha, 0.0f);  // sigma_t' = 1
      for (float r : {0.0f, 0.01f, 0.3f, 2.0f, 10.0f})
        EXPECT_EQ(bssrdf_radial_Rd(LUCENT_MODEL_STANDARD_DIPOLE, m, eta, r),
                  standard_dipole_Rd(m, eta, r) * standard_dipole_exit_normalization(eta));
      // 2 pi int r R_d(r) dr, midpoint rule in r over [0, 60 / sigma_tr].
      const double r_max = 60.0 / m.sigma_tr;
      const int n = 200000;
      double total = 0.0;
      for (int i = 0; i < n; ++i) {
        const double r = (i + 0.5) * r_max / n;
        total += 2.0 * M_PI * r * bssrdf_radial_Rd(LUCENT_MODEL_STANDARD_DIPOLE, m, eta, static_cast<float>(r)) * r_max / n;
      }
      const double closed = standard_dipole_total_Rd(m.alpha_prime, eta) * standard_dipole_exit_normalization(eta);
      EXPECT_NEAR(total, closed, 2e-3 * closed) << "alpha " << alpha << " eta " << eta;
    }
}

TEST(TextureSpaceIsRd, EveryModelIsPiTimesItsSdOnAFlatSurfaceAtNormalIncidence) {
  const BandMedium m = make_band_medium(0.05f, 2.0f, 0.0f);
  const vec3 n(0.0f, 0.0f, 1.0f);
  for (int model : {LUCENT_MODEL_STANDARD_DIPOLE, LUCENT_MODEL_DIRECTIONAL_DIPOLE, LUCENT_MODEL_PHOTON_BEAM_DIFFUSION})
    for (float r : {0.0f, 0.05f, 0.5f, 3.0f}) {
      const float R_d = bssrdf_radial_Rd(model, m, 1.3f, r);
      const float S_d = bssrdf_Sd(model, m, 1.3f, vec3(0.0f), n, n, vec3(r, 0.0f, 0.0f), n);
      EXPECT_TRUE(std::isfinite(R_d)) << model << " " << r;
      EXPECT_NEAR(R_d, kPi * S_d, 1e-6f * kPi * S_d) << "model " << model << " r " << r;
    }
}

// A size x size image (size a power of two) and its sum pyramid, level 0 first.
std::vector<std::vector<float>> sum_pyramid(const std::vector<float>& image, int size) {
  std::vector<std::vector<float>> levels{image};
  for (int s = size / 2; s >= 1; s /= 2) {
    const std::vector<float>& below = levels.back();
    std::vector<float> level(static_cast<std::size_t>(s * s));
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x) {
        auto at = [&](int dx, int dy) { return below[static_cast<std::size_t>((2 * y + dy) * 2 * s + 2 * x + dx)]; };
        level[static_cast<std::size_t>(y * s + x)] = at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1);
      }
    levels.push_back(level);
  }
  return levels;
}

// The descent sample.comp runs: from the 1 x 1 level to level 0.
ivec2 descend(const std::vector<std::vector<float>>& levels, int size, float u) {
  ivec2 t(0);
  for (int level = static_cast<int>(levels.size()) - 2; level >= 0; --level) {
    const int s = size >> level;
    const std::vector<float>& v = levels[static_cast<std::size_t>(level)];
    auto at = [&](ivec2 p) { return v[static_cast<std::size_t>(p.y * s + p.x)]; };
    const ivec2 c = 2 * t;
    const MipChoice choice =
        mip_choose_child(vec4(at(c), at(c + ivec2(1, 0)), at(c + ivec2(0, 1)), at(c + ivec2(1, 1))), u);
    t = c + mip_child_offset(choice.child);
    u = choice.u;
  }
  return t;
}

TEST(TextureSpaceIsSampling, MipmapDescentHistogramMatchesTheDensity) {
  const int size = 16;
  std::vector<float> image(static_cast<std::size_t>(size * size));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  double total = 0.0;
  for (std::size_t i = 0; i < image.size(); ++i) {
    // Empty texels (gutters, unlit), a wide range of values and a few hot spots.
    const float v = uniform(rng);
    image[i] = v < 0.3f ? 0.0f : (v > 0.97f ? 40.0f * v : v * v);
    total += image[i];
  }
  const auto levels = sum_pyramid(image, size);
  const int n = 400000;
  std::vector<int> histogram(image.size(), 0);
  for (int i = 0; i < n; ++i) {
    const ivec2 t = descend(levels, size, uniform(rng));
    ASSERT_TRUE(t.x >= 0 && t.y >= 0 && t.x < size && t.y < size);
    ++histogram[static_cast<std::size_t>(t.y * size + t.x)];
  }
  double chi2 = 0.0;
  int cells = 0;
  for (std::size_t i = 0; i < image.size(); ++i) {
    if (image[i] == 0.0f) {
      EXPECT_EQ(histogram[i], 0) << "texel " << i << " has no density";
      continue;
    }
    const double expected = n * image[i] / total;
    chi2 += (histogram[i] - expected) * (histogram[i] - expected) / expected;
    ++cells;
  }
  const double dof = cells - 1;
  // p ~ 1e-6 bound of the chi-square distribution (normal approximation, 5 standard deviations).
  EXPECT_LT(chi2, dof + 5.0 * std::sqrt(2.0 * dof)) << "cells " << cells;
}

TEST(TextureSpaceIsSampling, RoundingPastTheEndTakesTheLastNonEmptyChild) {
  const MipChoice c = mip_choose_child(vec4(1.0f, 2.0f, 0.0f, 0.0f), 0.99999994f);
  EXPECT_EQ(c.child, 1);
  EXPECT_GE(c.u, 0.0f);
  EXPECT_LT(c.u, 1.0f);
  EXPECT_EQ(mip_choose_child(vec4(0.0f, 0.0f, 3.0f, 1.0f), 0.0f).child, 2);
}

}  // namespace
