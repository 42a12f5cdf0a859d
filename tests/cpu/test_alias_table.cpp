// test_alias_table.cpp: the alias table gives each index its weight's share, exactly (up to rounding) and when
// sampled; the area sampling of the CPU references built on it is uniform over a mesh of unequal triangles.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "lucent/scene.h"
#include "reference/alias_table.h"
#include "reference/embree_scene.h"
#include "transport/rng.h"

namespace {

using lucent::reference::AliasTable;

TEST(AliasTable, ImpliedProbabilitiesEqualTheNormalisedWeights) {
  const std::vector<double> weights{0.0, 1.0, 7.5, 0.25, 3.0, 3.0, 1e-6, 12.0, 0.5};
  double total = 0.0;
  for (double w : weights) total += w;
  AliasTable table(weights);
  ASSERT_EQ(table.size(), weights.size());
  for (std::size_t i = 0; i < weights.size(); ++i) EXPECT_NEAR(table.probability(i), weights[i] / total, 1e-15) << i;
}

TEST(AliasTable, SampledFrequenciesMatchTheWeightsWithinFourSigma) {
  const std::vector<double> weights{5.0, 1.0, 0.0, 2.0, 8.0};
  AliasTable table(weights);
  lucent::reference::Rng rng(7, 1);
  const int n = 400000;
  std::vector<int> counts(weights.size(), 0);
  for (int k = 0; k < n; ++k) ++counts[table.sample(rng.uniform(), rng.uniform())];
  for (std::size_t i = 0; i < weights.size(); ++i) {
    const double p = weights[i] / 16.0, sigma = std::sqrt(n * p * (1.0 - p));
    EXPECT_LE(std::abs(counts[i] - n * p), 4.0 * sigma + 1e-9) << i;
  }
  EXPECT_EQ(counts[2], 0);  // a zero weight is never drawn
}

TEST(AliasTable, RefusesWeightsThatCannotBeNormalised) {
  EXPECT_THROW(AliasTable(std::vector<double>{}), std::invalid_argument);
  EXPECT_THROW(AliasTable(std::vector<double>{0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(AliasTable(std::vector<double>{1.0, -1.0}), std::invalid_argument);
  EXPECT_THROW(AliasTable(std::vector<double>{1.0, std::nan("")}), std::invalid_argument);
}

// A box of 40 x 10 x 2: faces of areas 400, 80 and 20 (mm^2) split in triangles of very different sizes. Uniform
// area sampling puts 400 / 1000 of the samples on the top and bottom each, 80 / 1000 on the long sides, 20 / 1000
// on the small ends.
TEST(AliasTable, AreaSamplingOfTheReferencesIsUniformOverTheSurface) {
  const lucent::Scene scene = lucent::parse_scene(
      R"({"objects": [{"shape": "box", "size": [40, 2, 10], "material": {"preset": "Marble"}}]})", "box", ".");
  lucent::reference::EmbreeScene rt(scene);
  EXPECT_NEAR(rt.object(0).area, 2.0 * (400.0 + 80.0 + 20.0), 1e-9);
  lucent::reference::Rng rng(3, 9);
  const int n = 200000;
  int top_bottom = 0, long_sides = 0, ends = 0;
  for (int k = 0; k < n; ++k) {
    auto s = rt.sample_surface(0, rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform());
    if (std::abs(std::abs(s.position.y) - 1.0) < 1e-6) ++top_bottom;
    else if (std::abs(std::abs(s.position.z) - 5.0) < 1e-6) ++long_sides;
    else if (std::abs(std::abs(s.position.x) - 20.0) < 1e-6) ++ends;
  }
  auto expect_share = [n](int count, double p) {
    EXPECT_LE(std::abs(count - n * p), 4.0 * std::sqrt(n * p * (1.0 - p))) << count << " of " << n << ", p " << p;
  };
  expect_share(top_bottom, 0.8);
  expect_share(long_sides, 0.16);
  expect_share(ends, 0.04);
  EXPECT_EQ(top_bottom + long_sides + ends, n);
}

}  // namespace
