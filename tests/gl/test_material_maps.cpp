// test_material_maps.cpp: textured materials on the GPU (media/material_map.h). The methods that read them evaluate
// eq. 9 with the coefficients at the exit point's texture coordinates, as the CPU references do
// (tests/cpu/test_material_maps.cpp). A sphere whose texture is split into two halves of different surface albedo
// is seen across the seam: with the same random numbers, every pixel renders as the untextured sphere of one half's
// albedo or of the other's, except in a band along the seam where the bilinear lookup (and for the maps their texel
// spacing) mixes them. Both halves must show, each matching its own material. The pixels that match are also
// compared as a whole: the mean over the textured image equals the mean of the matching uniform pixels.
#include <cmath>
#include <cstdio>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "image_compare.h"
#include "lucent/lucent.h"
#include "shared/tonemap.h"

namespace {

using lucent::ImageRGBA32F;

constexpr int kSize = 64;

std::string decoded(float r, float g, float b) {
  using lucent::shader::srgb_decode;
  return fmt::format("[{}, {}, {}]", srgb_decode(r / 255.0f), srgb_decode(g / 255.0f), srgb_decode(b / 255.0f));
}

std::string halves_png(const std::string& name, int left_r, int left_g, int left_b, int right_r, int right_g,
                       int right_b) {
  const std::string path = lucent::test::output_path(name);
  lucent::ImageRGBA8 image{64, 4, std::vector<std::uint8_t>(64 * 4 * 4)};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 64; ++x) {
      std::uint8_t* p = image.at(x, y);
      const bool left = x < 32;
      p[0] = static_cast<std::uint8_t>(left ? left_r : right_r), p[1] = static_cast<std::uint8_t>(left ? left_g : right_g);
      p[2] = static_cast<std::uint8_t>(left ? left_b : right_b), p[3] = 255;
    }
  lucent::write_png(path, image);
  return path;
}

// A material split into two halves by a map, and the untextured material of each half.
struct Split {
  std::string textured, left, right;
};

Split albedo_split() {
  const std::string png = halves_png("material_maps_albedo_halves.png", 235, 170, 110, 60, 100, 210);
  const std::string mfp = R"("mfp_mm": [0.8, 0.5, 0.3])";
  return {fmt::format(R"("albedo_map": "{}", {})", png, mfp),
          fmt::format(R"("albedo": {}, {})", decoded(235, 170, 110), mfp),
          fmt::format(R"("albedo": {}, {})", decoded(60, 100, 210), mfp)};
}

// Mean free path factors 1 and 0.2 on a scene of 10 mm per unit (the texels' mm become scene units on upload).
Split mfp_split() {
  const std::string png = halves_png("material_maps_mfp_halves.png", 255, 255, 255, 51, 51, 51);
  const std::string albedo = R"("albedo": [0.8, 0.6, 0.4])";
  return {fmt::format(R"("mfp_map": "{}", "mfp_mm": [0.8, 0.5, 0.3], {})", png, albedo),
          fmt::format(R"("mfp_mm": [0.8, 0.5, 0.3], {})", albedo),
          fmt::format(R"("mfp_mm": [0.16, 0.1, 0.06], {})", albedo)};
}


// The sphere seen from +x, across the seam of its texture (u = 0 | 1 along +x; u < 0.5 toward +z).
// A second translucent sphere behind the camera, out of view and out of the light's way: with two translucent
// objects the texture-space methods pack a chart atlas instead of using the sphere's own coordinates, so the
// material's coordinates must travel beside the atlas's (TriangleMesh::material_uvs).
constexpr const char* kHiddenSecondObject =
    R"(, { "shape": "sphere", "radius": 0.5, "translate": [12, 0, 0], "material": "Marble" })";

lucent::Scene sphere(const std::string& material, const std::string& method, const char* more_objects = "") {
  return lucent::parse_scene(fmt::format(R"({{
    "scale_mm": 10,
    "camera": {{ "eye": [6, 1, 0], "target": [0, 0, 0], "fov_y_deg": 22 }},
    "lights": [{{ "direction": [-1, -0.4, 0.2], "radiance": [1, 1, 1] }}],
    "objects": [{{ "shape": "sphere", "radius": 1, "segments": 96,
                   "material": {{ {}, "model": "standard" }} }}{}],
    "method": {},
    "render": {{ "width": {}, "height": {}, "frames": 4 }} }})",
                                         material, more_objects, method, kSize, kSize),
                             "textured sphere", "/");
}

ImageRGBA32F render(const lucent::Scene& scene) {
  lucent::OffscreenFramebuffer framebuffer(kSize, kSize);
  lucent::Renderer renderer(scene);
  for (int f = 0; f < scene.render.frames; ++f) renderer.render(scene.camera, {framebuffer.id(), kSize, kSize});
  return renderer.read_radiance();
}

// Each pixel's label: 0 matches neither half's material, 1 the left's only, 2 the right's only, 3 both.
std::vector<int> expect_each_half_renders_as_its_material(const std::string& method, const Split& split,
                                                          const char* more_objects = "") {
  lucent::test::ensure_gl_context();
  const ImageRGBA32F textured = render(sphere(split.textured, method, more_objects));
  const ImageRGBA32F left = render(sphere(split.left, method, more_objects));
  const ImageRGBA32F right = render(sphere(split.right, method, more_objects));
  std::vector<int> labels;
  int covered = 0, as_left = 0, as_right = 0, as_both = 0;
  double sum_textured = 0.0, sum_matched = 0.0;
  for (std::size_t i = 0; i < textured.pixels.size(); i += 4) {
    if (textured.pixels[i + 3] <= 0.0f) continue;  // background
    ++covered;
    double t = 0.0, l = 0.0, r = 0.0;
    for (int c = 0; c < 3; ++c) t += textured.pixels[i + c], l += left.pixels[i + c], r += right.pixels[i + c];
    // Within 1% of one material (or 1e-4 absolute in the dark): the same estimator with the same samples and
    // coefficients equal within the albedo inversion's 1e-4. Where the two materials render alike (a shorter
    // mean free path at the same albedo, lit head-on) a pixel matches both.
    const bool is_left = std::abs(t - l) <= 0.01 * l + 1e-4, is_right = std::abs(t - r) <= 0.01 * r + 1e-4;
    as_left += is_left && !is_right, as_right += is_right && !is_left, as_both += is_left && is_right;
    labels.push_back((is_left ? 1 : 0) + (is_right ? 2 : 0));
    if (is_left || is_right) sum_textured += t, sum_matched += is_left ? l : r;
  }
  const double f_left = double(as_left) / covered, f_right = double(as_right) / covered;
  const double f_both = double(as_both) / covered, f_neither = 1.0 - f_left - f_right - f_both;
  std::printf("%s: %d covered pixels, %.3f as the left half's material only, %.3f as the right half's only, %.3f as "
              "both, %.3f as neither (the seam); matched mean ratio %.6f\n",
              method.c_str(), covered, f_left, f_right, f_both, f_neither, sum_textured / sum_matched);
  EXPECT_GT(covered, kSize * kSize / 8);
  // Seen from +x each half covers about half of the disc, and each must show as its own material in a good part
  // of it; the seam band is a few texels wide.
  EXPECT_GT(f_left, 0.2);
  EXPECT_GT(f_right, 0.2);
  EXPECT_LT(f_neither, 0.15);
  EXPECT_NEAR(sum_textured / sum_matched, 1.0, 2e-3);
  return labels;
}

constexpr const char* kPerPixel = R"({"name": "per-pixel", "N": 16, "light_map_size": 128, "specular": false})";
constexpr const char* kRadiosityMaps =
    R"({"name": "radiosity-maps", "K": 8, "N": 16, "map_size": 128, "light_map_size": 128, "specular": false, "vpls": 0})";

TEST(MaterialMapsGpu, PerPixelTakesTheCoefficientsAtEachPixel) {
  expect_each_half_renders_as_its_material(kPerPixel, albedo_split());
  expect_each_half_renders_as_its_material(kPerPixel, mfp_split());
}

// Texture space: the atlas mesh replaces the sphere's, and the material's coordinates travel beside the atlas's.
constexpr const char* kTextureSpaceIs = R"({"name": "texture-space-is", "atlas_size": 256, "N": 256, "specular": false})";

TEST(MaterialMapsGpu, TextureSpaceIsTakesTheCoefficientsAtEachPixel) {
  for (const Split& split : {albedo_split(), mfp_split()}) {
    const std::vector<int> atlas = expect_each_half_renders_as_its_material(kTextureSpaceIs, split, kHiddenSecondObject);
    // The same pixels show the same half as per-pixel, which reads the sphere's own coordinates: an atlas's
    // coordinates in their place split the sphere elsewhere (charts packed side by side may even split it in
    // halves, so the fractions alone would not tell).
    const std::vector<int> own = expect_each_half_renders_as_its_material(kPerPixel, split, kHiddenSecondObject);
    ASSERT_EQ(atlas.size(), own.size());
    int disagree = 0;
    for (std::size_t i = 0; i < own.size(); ++i) disagree += (own[i] == 1 || own[i] == 2) && (atlas[i] == 1 || atlas[i] == 2) && own[i] != atlas[i];
    std::printf("pixels showing the other half than per-pixel: %d of %zu\n", disagree, own.size());
    EXPECT_LT(disagree, static_cast<int>(own.size()) / 100);
  }
}

TEST(MaterialMapsGpu, RadiosityMapsTakeTheCoefficientsAtEachMapTexel) {
  expect_each_half_renders_as_its_material(kRadiosityMaps, albedo_split());
  expect_each_half_renders_as_its_material(kRadiosityMaps, mfp_split());
}

TEST(MaterialMapsGpu, OtherMethodsRefuseTexturedMaterials) {
  lucent::test::ensure_gl_context();
  const lucent::Scene scene = sphere(albedo_split().textured, R"({"name": "diffuse-wrap"})");
  std::string message;
  try {
    lucent::Renderer renderer(scene);
  } catch (const lucent::Error& e) {
    message = e.what();
  }
  EXPECT_EQ(message, "textured sphere: /objects/0/material/albedo_map: method 'diffuse-wrap' does not read textured "
                     "materials (methods that do: radiosity-maps, per-pixel, texture-space-is; the references lucent reference "
                     "--integrator volpath|bssrdf do)");
}

}  // namespace
