// test_layer_parallax.cpp: the depth parallax of layered-parallax (media/layer_parallax.h, Norberg Eqs. 15-19)
// against geometry: with a flat normal the inner layer is seen where the straight line of sight meets a plane d
// below the surface (offset -d tan(theta) toward the viewer's azimuth, distance d / cos(theta)); a tilted normal
// bends the line of sight away from the tilt's mirror; grazing views are bounded; the blend follows N . V.
#include <cmath>

#include <gtest/gtest.h>

#include "media/layer_parallax.h"

namespace {

using namespace lucent::shader;

TEST(LayerParallax, FlatNormalContinuesTheLineOfSight) {
  const float depth = 0.7f;
  for (float theta : {0.0f, 0.3f, 0.8f, 1.2f}) {
    const float phi = 0.9f;
    const glm::vec3 view(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    const glm::vec3 t = parallax_transmission(view, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_NEAR(t.x, -view.x, 1e-6f);
    EXPECT_NEAR(t.y, -view.y, 1e-6f);
    EXPECT_NEAR(t.z, -view.z, 1e-6f);
    const glm::vec3 o = parallax_offset(t, depth, 0.05f);
    // Where the line of sight from the surface point meets the plane z = -depth.
    EXPECT_NEAR(o.x, -depth * std::tan(theta) * std::cos(phi), 1e-5f) << theta;
    EXPECT_NEAR(o.y, -depth * std::tan(theta) * std::sin(phi), 1e-5f) << theta;
    EXPECT_NEAR(o.z, depth / std::cos(theta), 1e-5f) << theta;
  }
}

TEST(LayerParallax, TiltedNormalBendsTheLineOfSight) {
  // Seen from straight above, a normal tilted toward +x reflects the view about itself toward +x, and T keeps that
  // lateral part: the inner layer is read displaced toward the tilt.
  const glm::vec3 n = glm::normalize(glm::vec3(0.2f, 0.0f, 1.0f));
  const glm::vec3 t = parallax_transmission(glm::vec3(0.0f, 0.0f, 1.0f), n);
  EXPECT_GT(t.x, 0.0f);
  EXPECT_NEAR(t.y, 0.0f, 1e-7f);
  EXPECT_LT(t.z, 0.0f);
  EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f);
}

TEST(LayerParallax, GrazingViewsAreBoundedAndFadeOut) {
  const glm::vec3 view(std::sin(1.565f), 0.0f, std::cos(1.565f));  // 0.3 degrees above the surface
  const glm::vec3 o = parallax_offset(parallax_transmission(view, glm::vec3(0.0f, 0.0f, 1.0f)), 1.0f, 0.05f);
  EXPECT_NEAR(o.z, 1.0f / 0.05f, 1e-4f);
  EXPECT_LT(std::fabs(o.x), 20.0f + 1e-4f);
  EXPECT_NEAR(parallax_inner_weight(0.8f, glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f, 0.0f, 1.0f)), 0.8f, 1e-7f);
  EXPECT_LT(parallax_inner_weight(0.8f, glm::vec3(0.0f, 0.0f, 1.0f), view), 0.01f);
  EXPECT_EQ(parallax_inner_weight(0.8f, glm::vec3(0.0f, 0.0f, 1.0f), -view), 0.0f);
}

}  // namespace
