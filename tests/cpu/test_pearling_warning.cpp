// test_pearling_warning.cpp: radiosity-maps' pearling warning advises a light-map size that avoids pearling and that
// the parameter allows, or says that none does.
#include <gtest/gtest.h>

#include "methods/radiosity_maps/pearling_warning.h"

using lucent::methods::pearling_warning;

TEST(PearlingWarning, NoneWhenTheLengthSpansTwoTexels) {
  EXPECT_EQ(pearling_warning("Bunny", 1.0, 0.5, 512, 8192), "");
}

TEST(PearlingWarning, AdvisesASizeThatAvoidsIt) {
  // 2 x 0.4 mm / 0.5 mm x 512 = 819.2 texels: 820; there a texel is 0.4 x 512 / 820 = 0.2498 mm, two under 0.5 mm.
  EXPECT_EQ(pearling_warning("Bunny", 0.5, 0.4, 512, 8192),
            "Bunny: scattering length 0.5 mm is under 2 light-map texels (0.4 mm each); expect "
            "pearling, or raise method.light_map_size to 820");
  EXPECT_EQ(pearling_warning("Bunny", 0.5, 0.4 * 512.0 / 820.0, 820, 8192), "");
}

TEST(PearlingWarning, SaysSoWhenNoAllowedSizeAvoidsIt) {
  // 2 x 1 mm / 0.01 mm x 512 = 102400 texels, over the largest 8192, where a texel is 512 / 8192 mm = 0.0625 mm.
  EXPECT_EQ(pearling_warning("Bunny", 0.01, 1.0, 512, 8192),
            "Bunny: scattering length 0.01 mm is under 2 light-map texels (1 mm each); expect "
            "pearling: method.light_map_size would have to be 1.02e+05; its largest value, 8192, gives 0.0625 mm "
            "texels");
}
