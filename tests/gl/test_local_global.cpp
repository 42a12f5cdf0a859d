// test_local_global.cpp: the local-global method (Lensch et al. 2002) on the GPU: a flat slab under uniform
// irradiance converges to the model's total diffuse reflectance with blending (Section 5.4), and without blending
// double counts the near field (the paper's Fig. 6, "much too bright"); deforming objects are refused with one line.
//
// The slab is the one of test_flat_slab.cpp (same material, light and camera: L = F_t(eta, 1) E R_total F_t /
// (pi (1 - 2 C1(1/eta))) at its centre, R_total the standard dipole's closed form), but as a tessellated square of 4 x 4 mm: the global
// response lives on mesh vertices, so the box shape's two triangles per face would carry none of it.
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "../flat_slab_expectation.h"
#include "../temp_cache_dir.h"
#include "image_compare.h"
#include "lucent/lucent.h"

namespace {

using namespace lucent::test::flat_slab;

// A square of `extent` scene units in the xz plane at height y, n x n quads, normal +y, texture coordinates over
// [0, 1]^2 (so the atlas is the square itself, one chart).
lucent::TriangleMesh grid(float extent, int n, float y) {
  lucent::TriangleMesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float u = static_cast<float>(i) / static_cast<float>(n), v = static_cast<float>(j) / static_cast<float>(n);
      mesh.positions.emplace_back((u - 0.5f) * extent, y, (0.5f - v) * extent);
      mesh.normals.emplace_back(0.0f, 1.0f, 0.0f);
      mesh.uvs.emplace_back(u, v);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = static_cast<std::uint32_t>(j * (n + 1) + i), b = a + 1,
                          c = a + static_cast<std::uint32_t>(n + 1), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  return mesh;
}

lucent::Scene slab_scene(const std::string& method_keys, int quads) {
  const std::string json = fmt::format(R"({{
    "scale_mm": 10,
    "camera": {{ "eye": [0, 3.1, 0], "target": [0, 0.1, 0], "up": [0, 0, -1], "fov_y_deg": 1.91 }},
    "lights": [{{ "direction": [0, -1, 0], "radiance": [{}, {}, {}] }}],
    "objects": [{{ "name": "slab", "shape": "plane", "extent": [0.4, 0.4], "translate": [0, 0.1, 0],
                  "material": {{ "sigma_a": [{}, {}, {}], "sigma_s": [{}, {}, {}], "g": 0, "eta": {},
                                "model": "standard" }} }}],
    "method": {{ "name": "local-global", {}, "light_map_size": 256, "specular": false }},
    "render": {{ "width": {}, "height": {}, "frames": 1, "seed": 1 }} }})",
                                       kIrradiance[0], kIrradiance[1], kIrradiance[2], kSigmaA[0], kSigmaA[1], kSigmaA[2],
                                       kSigmaS[0], kSigmaS[1], kSigmaS[2], kEta, method_keys, kSize, kSize);
  lucent::Scene scene = lucent::parse_scene(json, "flat slab scene", ".");
  scene.objects[0].mesh = grid(0.4f, quads, 0.0f);
  return scene;
}

// Mean radiance per band over the image (all of it shows the slab's centre) divided by the expected value.
std::array<double, 3> slab_ratio(const std::string& method_keys, int quads) {
  const lucent::Scene scene = slab_scene(method_keys, quads);
  lucent::OffscreenFramebuffer framebuffer(kSize, kSize);
  lucent::Renderer renderer(scene);
  renderer.render(scene.camera, {framebuffer.id(), kSize, kSize});
  const lucent::ImageRGBA32F image = renderer.read_radiance();
  std::array<double, 3> sum{};
  int n = 0;
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
    EXPECT_GT(image.pixels[i + 3], 0.5f) << "pixel " << i / 4 << " does not show the slab";
    for (std::size_t b = 0; b < 3; ++b) sum[b] += image.pixels[i + b];
    ++n;
  }
  std::array<double, 3> ratio{};
  for (std::size_t b = 0; b < 3; ++b) ratio[b] = sum[b] / n / expected_radiance(b);
  return ratio;
}

class LocalGlobal : public ::testing::Test {
 protected:
  void SetUp() override { lucent::test::ensure_gl_context(); }
  lucent::test::TempCacheDir cache_;
};

// 32 x 32 quads (125 um edges) on an atlas of 64 texels (62.5 um): the kernels reach the neighbouring vertices
// (tests/cpu/test_local_global_cpu.cpp measures coarser triangles). Measured on llvmpipe: 1.0022 1.0053 1.0080, the
// CPU evaluation of the same tables to 4 digits; tolerance 2%. Vertex irradiance 10% low (dual weights times 0.9) fails it.
TEST_F(LocalGlobal, FlatSlabConvergesToTheTotalDiffuseReflectance) {
  const auto ratio = slab_ratio(R"("atlas_size": 64, "cutoff": 1e-4)", 32);
  std::printf("local-global on the flat slab: radiance / expected = %.4f %.4f %.4f\n", ratio[0], ratio[1], ratio[2]);
  for (std::size_t b = 0; b < 3; ++b) EXPECT_NEAR(ratio[b], 1.0, 0.02) << "band " << b;
}

// `show` (the paper's Fig. 8): the local and the global responses each reach the image alone, and they add up to
// the combined image (on the flat slab both parts are positive, so the final clamp does not act).
TEST_F(LocalGlobal, ShowLocalAndGlobalAddUpToTheCombinedResponse) {
  const std::string keys = R"("atlas_size": 64, "cutoff": 1e-4)";
  const auto combined = slab_ratio(keys, 32);
  const auto local = slab_ratio(keys + R"(, "show": "local")", 32);
  const auto global = slab_ratio(keys + R"(, "show": "global")", 32);
  std::printf("local-global parts on the flat slab: local %.4f global %.4f combined %.4f (green)\n", local[1], global[1],
              combined[1]);
  for (std::size_t b = 0; b < 3; ++b) {
    EXPECT_GT(local[b], 0.05) << "band " << b;
    EXPECT_GT(global[b], 0.05) << "band " << b;
    EXPECT_NEAR(local[b] + global[b], combined[b], 1e-4) << "band " << b;
  }
}

TEST_F(LocalGlobal, WithoutBlendingTheNearFieldIsCountedTwice) {
  const auto ratio = slab_ratio(R"("atlas_size": 64, "cutoff": 1e-4, "blend": false)", 32);
  std::printf("local-global without blending on the flat slab: radiance / expected = %.4f %.4f %.4f\n", ratio[0],
              ratio[1], ratio[2]);
  for (std::size_t b = 0; b < 3; ++b) EXPECT_GT(ratio[b], 1.05) << "band " << b;
}

TEST_F(LocalGlobal, ADeformingObjectIsRefusedWithOneLine) {
  lucent::Scene scene = slab_scene(R"("atlas_size": 32)", 4);
  scene.objects[0].deformation.type = lucent::DeformationType::Bend;
  try {
    lucent::Renderer renderer(scene);
    FAIL() << "no error";
  } catch (const lucent::Error& e) {
    EXPECT_STREQ(e.what(), "flat slab scene: object 'slab': local-global precomputes transport over a fixed mesh; "
                           "deforming objects are not supported (rigid objects only)");
  }
}

}  // namespace
