// test_material_maps.cpp: textured translucent materials (lucent/material.h MaterialMaps,
// materials/material_maps.h): the per-texel inversion against the model's exact flat total, the texture lookup's
// conventions (bilinear between texel centres, repeating, v = 0 at the bottom row, sRGB colour), the scene syntax
// and its one-line errors, and both CPU references against the untextured material.
//
// The references evaluate a textured material where the light leaves the surface (S_d's exit point; volpath's
// walk takes the medium of the point where the camera path entered). On a convex object no path re-enters, so a
// pixel whose surface point lies in a texture region of albedo A renders exactly as the untextured material of
// albedo A: with the same random numbers the two estimates differ only by the inversion's 1e-4.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../test_support.h"
#include "lucent/error.h"
#include "lucent/image.h"
#include "lucent/scene.h"
#include "lucent/scene_writer.h"
#include "materials/artist_parameters.h"
#include "materials/material_maps.h"
#include "methods/method_info.h"
#include "reference/embree_scene.h"
#include "reference/integrators.h"
#include "reference/reference_cache.h"
#include "reference/reference_renderer.h"
#include "shared/tonemap.h"
#include "transport/estimate.h"

namespace lucent {
namespace {

using test::TempFile;
using test::error_message;

// A width x height PNG whose left half is `left` and right half `right` (8-bit sRGB values).
void write_halves_png(const std::string& path, int width, int height, glm::u8vec3 left, glm::u8vec3 right) {
  ImageRGBA8 image{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(4 * width * height))};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::u8vec3 c = x < width / 2 ? left : right;
      std::uint8_t* p = image.at(x, y);
      p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = 255;
    }
  write_png(path, image);
}

glm::vec3 decoded(glm::u8vec3 c) {
  return {shader::srgb_decode(c.r / 255.0f), shader::srgb_decode(c.g / 255.0f), shader::srgb_decode(c.b / 255.0f)};
}

std::string vec_json(glm::vec3 v) { return fmt::format("[{}, {}, {}]", v.x, v.y, v.z); }

Scene sphere_scene(const std::string& material_json, double scale_mm = 1.0) {
  return parse_scene(fmt::format(R"({{
    "scale_mm": {},
    "lights": [{{ "direction": [0.3, -1, 0.2], "radiance": [2, 2, 2] }}],
    "objects": [{{ "shape": "sphere", "radius": 5, "segments": 48, "material": {} }}] }})",
                                 scale_mm, material_json),
                     "maps-test", "/");
}

TEST(MaterialMaps, AlbedoCurveInvertsTheExactFlatTotal) {
  struct Case {
    BssrdfModel model;
    float g, eta;
  };
  const Case cases[] = {{BssrdfModel::StandardDipole, 0.0f, 1.3f},     {BssrdfModel::StandardDipole, 0.8f, 1.0f},
                        {BssrdfModel::DirectionalDipole, 0.0f, 1.3f},  {BssrdfModel::DirectionalDipole, -0.3f, 1.5f},
                        {BssrdfModel::BetterDipole, 0.5f, 1.4f},       {BssrdfModel::PhotonBeamDiffusion, 0.0f, 1.3f}};
  double worst = 0.0;
  for (const Case& c : cases) {
    const AlbedoCurve curve(c.model, c.g, c.eta);
    for (double albedo = 0.05; albedo < 0.951; albedo += 0.05) {
      if (albedo <= curve.lowest() || albedo >= curve.highest()) continue;  // outside what the model reaches
      const double alpha = curve.alpha(albedo);
      const double total = flat_total_of_albedo(c.model, alpha, c.g, c.eta);
      worst = std::max(worst, std::abs(total - albedo));
      EXPECT_NEAR(total, albedo, 1e-4) << to_string(c.model) << " g " << c.g << " eta " << c.eta;
    }
  }
  std::printf("largest |total(alpha(A)) - A| over the cases: %.2e\n", worst);
}

TEST(MaterialMaps, TexelsHoldTheUniformInversionAndTheLookupFollowsTheConventions) {
  TempFile png(".png");
  const glm::u8vec3 left{200, 120, 60}, right{90, 160, 230};
  write_halves_png(png.path(), 64, 2, left, right);
  const Scene scene = sphere_scene(fmt::format(R"({{ "albedo_map": "{}", "mfp_mm": [1, 0.5, 0.25],
                                                    "model": "standard" }})", png.path()));
  const Material& m = *scene.objects[0].material;
  ASSERT_TRUE(m.textured());
  const MaterialMaps& maps = *m.maps;
  EXPECT_EQ(maps.alpha_size, glm::ivec2(64, 2));
  for (auto [colour, u] : {std::pair{left, 0.2f}, std::pair{right, 0.8f}}) {
    ArtistParameters artist;
    artist.albedo = decoded(colour);
    artist.mfp_mm = {1.0f, 0.5f, 0.25f};
    artist.model = BssrdfModel::StandardDipole;
    const Material uniform = invert_artist_parameters(artist, "uniform").material;
    glm::vec3 sigma_a, sigma_s;
    maps.coefficients({u, 0.5f}, sigma_a, sigma_s);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(sigma_a[c], uniform.sigma_a[c], 2e-3 * uniform.sigma_t()[c]) << "band " << c << " u " << u;
      EXPECT_NEAR(sigma_s[c], uniform.sigma_s[c], 2e-3 * uniform.sigma_t()[c]) << "band " << c << " u " << u;
    }
  }
  // Bilinear between texel centres: u = 0.5 is halfway between texels 31 and 32; repeating: u + 1 is u.
  const glm::vec3 mid = maps.alpha_at({0.5f, 0.5f});
  EXPECT_NEAR(mid.r, 0.5f * (maps.alpha_at({0.2f, 0.5f}).r + maps.alpha_at({0.8f, 0.5f}).r), 1e-6f);
  for (float u : {1.2f, -0.8f})
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(maps.alpha_at({u, 0.5f})[c], maps.alpha_at({0.2f, 0.5f})[c], 1e-6f) << u;
}

TEST(MaterialMaps, RowsRunFromTheBottomUp) {
  // A 1 x 2 EXR of mean free path factors: the top row (stored first) 4, the bottom row 1.
  TempFile exr(".exr");
  ImageRGBA32F image{1, 2, {4, 4, 4, 1, 1, 1, 1, 1}};
  write_exr(exr.path(), image);
  const Scene scene = sphere_scene(fmt::format(R"({{ "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1.9, 1.9, 1.9],
                                                    "mfp_map": "{}" }})", exr.path()));
  const MaterialMaps& maps = *scene.objects[0].material->maps;
  EXPECT_FLOAT_EQ(maps.mfp_mm_at({0.5f, 0.25f}).x, 0.5f);  // bottom row: factor 1 on mfp 1 / 2 mm
  EXPECT_FLOAT_EQ(maps.mfp_mm_at({0.5f, 0.75f}).x, 2.0f);  // top row: factor 4
  EXPECT_FLOAT_EQ(maps.alpha_at({0.5f, 0.25f}).x, 0.95f);  // no albedo map: the material's alpha everywhere
  // The material's own coefficients are those at the map's mean factor 2.5.
  EXPECT_NEAR(scene.objects[0].material->sigma_t().x, 2.0f / 2.5f, 1e-6f);
}

TEST(MaterialMaps, BadMapsGetOneLine) {
  TempFile png(".png");
  write_halves_png(png.path(), 4, 1, {200, 150, 120}, {150, 180, 230});
  const std::string where = "maps-test: /objects/0/material";
  auto load = [&](const std::string& material) { return error_message([&] { sphere_scene(material); }); };
  EXPECT_EQ(load(fmt::format(R"({{ "albedo_map": "{}", "albedo": 0.5, "mfp_mm": 1 }})", png.path())),
            where + "/albedo: not allowed with albedo_map (the map is the surface albedo)");
  EXPECT_EQ(load(fmt::format(R"({{ "albedo_map": "{}" }})", png.path())),
            where + "/mfp_mm: missing; albedo_map needs the mean free path too, e.g. [1, 0.5, 0.25]");
  EXPECT_EQ(load(fmt::format(R"({{ "albedo_map": "{}", "mfp_mm": 1, "model": "tabulated" }})", png.path())),
            where + "/model: tabulated takes no albedo_map: its tables hold one medium each, a texture has a medium "
                    "per texel");
  EXPECT_EQ(load(fmt::format(R"({{ "albedo_map": "{}", "mfp_mm": 1, "field": {{ "type": "marble" }} }})", png.path())),
            where + "/field: not with albedo_map: a material is textured or has a 3D field, not both");
  EXPECT_EQ(load(R"({ "albedo_map": "/nonexistent/a.png", "mfp_mm": 1 })"),
            where + "/albedo_map: /nonexistent/a.png: cannot read PNG: No such file or directory");
  EXPECT_EQ(load(R"({ "albedo_map": "/nonexistent/a.tga", "mfp_mm": 1 })"),
            where + "/albedo_map: /nonexistent/a.tga: unknown image type '.tga'; a map is .png, .exr or .hdr");
  TempFile zero(".zero.exr");
  write_exr(zero.path(), ImageRGBA32F{2, 1, {1, 1, 1, 1, 1, 0, 1, 1}});
  const float skim_mfp = 1.0f / material_from_preset(*find_material_preset("Skimmilk")).sigma_t()[1];
  EXPECT_EQ(load(fmt::format(R"({{ "preset": "Skimmilk", "mfp_map": "{}" }})", zero.path())),
            fmt::format("{}/mfp_map: {}: texel (1, 0) band 1 scales the mean free path {} mm to 0 mm; allowed "
                        "range (1e-30, 1e+30) mm: a map value of 0 is no mean free path",
                        where, zero.path(), skim_mfp));
  // A finite mean free path beyond the bound: the message states the bound, not "inf".
  TempFile huge(".huge.exr");
  write_exr(huge.path(), ImageRGBA32F{1, 1, {1, 1.2e30f / skim_mfp, 1, 1}});
  const std::string huge_message = load(fmt::format(R"({{ "preset": "Skimmilk", "mfp_map": "{}" }})", huge.path()));
  EXPECT_NE(huge_message.find("band 1 scales the mean free path"), std::string::npos) << huge_message;
  EXPECT_NE(huge_message.find("mm; allowed range (1e-30, 1e+30) mm"), std::string::npos) << huge_message;
  TempFile wide(".wide.exr");
  write_exr(wide.path(), ImageRGBA32F{4097, 1, std::vector<float>(4 * 4097, 1.0f)});
  EXPECT_EQ(load(fmt::format(R"({{ "preset": "Skimmilk", "mfp_map": "{}" }})", wide.path())),
            fmt::format("{}/mfp_map: {}: map is 4097x1; a material map may have at most 4096 texels on each side",
                        where, wide.path()));
  TempFile negative(".negative.exr");
  write_exr(negative.path(), ImageRGBA32F{1, 1, {1, -1, 1, 1}});
  EXPECT_EQ(load(fmt::format(R"({{ "preset": "Skimmilk", "mfp_map": "{}" }})", negative.path())),
            fmt::format("{}/mfp_map: {}: texel (0, 0) band 1 = -1; map values are finite and >= 0", where,
                        negative.path()));
}

TEST(MaterialMaps, AMeshWithoutTextureCoordinatesIsRefused) {
  TempFile png(".png"), obj(".obj");
  write_halves_png(png.path(), 4, 1, {200, 150, 120}, {150, 180, 230});
  {
    std::FILE* f = std::fopen(obj.path().c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", f);
    std::fclose(f);
  }
  const std::string message = error_message([&] {
    parse_scene(fmt::format(R"({{ "objects": [{{ "mesh": "{}", "material": {{ "albedo_map": "{}", "mfp_mm": 1 }} }}] }})",
                            obj.path(), png.path()),
                "maps-test", "/");
  });
  EXPECT_EQ(message, fmt::format("maps-test: /objects/0/material/albedo_map: a texture needs the mesh's texture "
                                 "coordinates; {} has none",
                                 obj.path()));
}

TEST(MaterialMaps, AlbedosOutsideTheModelsRangeAreClampedWithOneWarning) {
  TempFile png(".png");
  write_halves_png(png.path(), 4, 1, {0, 0, 0}, {128, 128, 128});  // black: below every model's smallest total
  ::testing::internal::CaptureStderr();
  const Scene scene = sphere_scene(fmt::format(R"({{ "albedo_map": "{}", "mfp_mm": 1, "model": "standard" }})",
                                               png.path()));
  const std::string warning = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(warning.find("lucent: warning: maps-test: /objects/0/material/albedo_map: " + png.path() +
                         ": 6 of 12 texel values are outside the surface albedos the standard model reaches"),
            std::string::npos)
      << warning;
  // Clamped a thousandth of the reachable range inside it, as the material's mean is.
  const AlbedoCurve curve(BssrdfModel::StandardDipole, 0.0f, ArtistParameters{}.eta);
  EXPECT_GT(scene.objects[0].material->maps->alpha_at({0.125f, 0.5f}).x, kArtistAlphaMin);
  EXPECT_NEAR(scene.objects[0].material->maps->alpha_at({0.125f, 0.5f}).x,
              curve.alpha(curve.lowest() + 1e-3 * (std::min(1.0, curve.highest()) - curve.lowest())), 1e-6);
}

// A surface albedo above 1 is a mistake in the map (e.g. an unnormalized HDR export), not a value to clamp.
TEST(MaterialMaps, AlbedosAboveOneAreRefusedNamingTheTexel) {
  TempFile exr(".bright.exr");
  write_exr(exr.path(), ImageRGBA32F{2, 1, {0.5f, 0.5f, 0.5f, 1, 0.5f, 2, 0.5f, 1}});
  EXPECT_EQ(error_message([&] { sphere_scene(fmt::format(R"({{ "albedo_map": "{}", "mfp_mm": 1 }})", exr.path())); }),
            fmt::format("maps-test: /objects/0/material/albedo_map: {}: texel (1, 0) band 1 = 2; a surface albedo is "
                        "at most 1 (a surface reflects at most the light that reaches it)",
                        exr.path()));
}

// A white map (albedo 1 everywhere, beyond the 0.998 the standard dipole reaches) over a floor: both references
// stay finite.
// Texels at the range's very end (alpha 1 - 1e-7) rounded to no absorption in float; the bssrdf reference's
// probes then spread over an infinite plane and sent Embree rays from infinity (an abort, not an error).
TEST(MaterialMaps, AWhiteMapOverAFloorRendersFiniteInBothReferences) {
  TempFile png(".white.png");
  write_halves_png(png.path(), 8, 8, {255, 255, 255}, {255, 255, 255});
  ::testing::internal::CaptureStderr();
  const Scene scene = parse_scene(fmt::format(R"({{
    "scale_mm": 20,
    "camera": {{ "eye": [0, 1.2, 4.6], "target": [0, 0.75, 0], "fov_y_deg": 34 }},
    "lights": [{{ "direction": [0.75, -0.5, -0.45], "radiance": [3, 2.9, 2.7] }}],
    "objects": [{{ "shape": "sphere", "radius": 0.75, "segments": 32, "translate": [0, 0.75, 0],
                   "material": {{ "albedo_map": "{}", "mfp_mm": [1.2, 0.8, 0.55], "eta": 1.5, "model": "standard" }} }},
                 {{ "shape": "plane", "extent": [12, 12], "albedo": [0.45, 0.45, 0.48] }}],
    "render": {{ "width": 24, "height": 16 }} }})", png.path()), "white-map", "/");
  ::testing::internal::GetCapturedStderr();
  for (auto integrator : {reference::Integrator::Bssrdf, reference::Integrator::Volpath}) {
    reference::ReferenceSettings settings;
    settings.integrator = integrator;
    settings.samples_per_pixel = 4;
    const reference::ReferenceImage image = reference::render_reference(scene, settings);
    double sum = 0.0;
    for (std::size_t i = 0; i < image.mean.pixels.size(); ++i) {
      ASSERT_TRUE(std::isfinite(image.mean.pixels[i])) << i;
      if (i % 4 != 3) sum += image.mean.pixels[i];
    }
    EXPECT_GT(sum, 0.0) << reference::to_string(integrator);
  }
}

TEST(MaterialMaps, MethodsThatDoNotReadMapsAreRefused) {
  TempFile png(".png");
  write_halves_png(png.path(), 4, 1, {200, 150, 120}, {150, 180, 230});
  const Scene scene = sphere_scene(fmt::format(R"({{ "albedo_map": "{}", "mfp_mm": 1 }})", png.path()));
  for (const methods::MethodInfo* method : methods::method_registry()) {
    if (method->reads_material_maps) continue;
    EXPECT_EQ(error_message([&] { methods::refuse_material_maps(scene, *method); }),
              fmt::format("maps-test: /objects/0/material/albedo_map: method '{}' does not read textured materials "
                          "(methods that do: radiosity-maps, per-pixel, texture-space-is; the references lucent reference "
                          "--integrator volpath|bssrdf do)",
                          method->name));
  }
}

TEST(MaterialMaps, TheSceneWriterKeepsTheMaps) {
  TempFile png(".png"), exr(".exr");
  write_halves_png(png.path(), 8, 2, {235, 170, 110}, {60, 100, 210});
  write_exr(exr.path(), ImageRGBA32F{2, 1, {1, 1, 1, 1, 0.5f, 0.5f, 0.5f, 1}});
  for (const std::string& material :
       {fmt::format(R"({{ "albedo_map": "{}", "mfp_map": "{}", "mfp_mm": [1, 0.5, 0.25], "g": 0.3, "eta": 1.4,
                      "model": "standard" }})", png.path(), exr.path()),
        fmt::format(R"({{ "preset": "Skimmilk", "mfp_map": "{}" }})", exr.path())}) {
    const Scene scene = sphere_scene(material);
    TempFile saved(".json");
    save_scene(scene, saved.path());
    const Scene again = load_scene(saved.path());
    std::error_code ignored;
    std::filesystem::remove_all(saved.path().substr(0, saved.path().size() - 5) + ".meshes", ignored);
    const std::string written = nlohmann::json::parse(std::ifstream(saved.path())).dump();
    const Material &a = *scene.objects[0].material, &b = *again.objects[0].material;
    ASSERT_TRUE(b.textured()) << written;
    EXPECT_EQ(a.maps->albedo_file, b.maps->albedo_file);
    EXPECT_EQ(a.maps->mfp_file, b.maps->mfp_file);
    EXPECT_EQ(a.g, b.g);
    EXPECT_EQ(a.eta, b.eta);
    EXPECT_EQ(a.model, b.model);
    for (glm::vec2 uv : {glm::vec2(0.1f, 0.3f), glm::vec2(0.8f, 0.6f)}) {
      glm::vec3 sa, ss, ta, ts;
      a.maps->coefficients(uv, sa, ss);
      b.maps->coefficients(uv, ta, ts);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(ta[c], sa[c], 1e-5f * (sa[c] + ss[c])) << written;
        EXPECT_NEAR(ts[c], ss[c], 1e-5f * (sa[c] + ss[c])) << written;
      }
    }
  }
}

// Radiance of camera rays toward points of the sphere at azimuth fraction u (the sphere's texture u) and
// latitude 30 degrees, from outside along the normal; the same random numbers for every scene.
reference::Estimate sphere_radiance(const Scene& scene, bool volpath, double u, int samples, std::vector<double>* each) {
  reference::EmbreeScene rt(scene);
  const reference::ReferenceScene rs{scene, rt};
  reference::Accumulator acc;
  for (int i = 0; i < samples; ++i) {
    reference::Rng rng(29, static_cast<std::uint64_t>(i));
    const double phi = 2.0 * M_PI * (u + 0.04 * (rng.uniform() - 0.5)), lat = (30.0 + 20.0 * (rng.uniform() - 0.5)) * M_PI / 180.0;
    // The sphere's u runs with atan2(z, x) or its mirror; the hit's own uv is checked below.
    const glm::dvec3 n(std::cos(lat) * std::cos(phi), std::sin(lat), std::cos(lat) * std::sin(phi));
    const reference::SurfaceHit hit = rt.intersect(15.0 * n, -n);
    if (!hit.hit()) continue;
    const glm::dvec3 L = volpath ? reference::volpath_radiance(rs, 15.0 * n, -n, rng, &hit)
                                 : reference::bssrdf_radiance(rs, 15.0 * n, -n, rng, &hit);
    acc.add(L.x + L.y + L.z);
    if (each) each->push_back(L.x + L.y + L.z);
  }
  return acc.estimate();
}

// Which texture half the points at azimuth fraction u fall in (the sphere's u may run either way round).
double texture_u_of(const Scene& scene, double u) {
  reference::EmbreeScene rt(scene);
  const double phi = 2.0 * M_PI * u, lat = 30.0 * M_PI / 180.0;
  const glm::dvec3 n(std::cos(lat) * std::cos(phi), std::sin(lat), std::cos(lat) * std::sin(phi));
  return rt.intersect(15.0 * n, -n).uv.x;
}

// A texture split into two halves, and the untextured material of each half.
struct SplitCase {
  const char* name;
  double scale_mm;        // the scene's mm per unit: the maps' coefficients must follow it
  std::string textured;   // material JSON with the map
  std::string left, right;
};

SplitCase albedo_split(const std::string& png) {
  const glm::u8vec3 left{235, 170, 110}, right{60, 100, 210};
  write_halves_png(png, 64, 4, left, right);
  const std::string common = R"("mfp_mm": [0.8, 0.5, 0.3], "model": "standard", "eta": 1.3)";
  return {"albedo map", 1.0, fmt::format(R"({{ "albedo_map": "{}", {} }})", png, common),
          fmt::format(R"({{ "albedo": {}, {} }})", vec_json(decoded(left)), common),
          fmt::format(R"({{ "albedo": {}, {} }})", vec_json(decoded(right)), common)};
}

// Mean free path factors 1 (255) and 0.2 (51, a denser half) on a scene of 0.5 mm per unit.
SplitCase mfp_split(const std::string& png) {
  write_halves_png(png, 64, 4, {255, 255, 255}, {51, 51, 51});
  const std::string common = R"("albedo": [0.8, 0.6, 0.4], "model": "standard", "eta": 1.3)";
  return {"mfp map", 0.5, fmt::format(R"({{ "mfp_map": "{}", "mfp_mm": [0.8, 0.5, 0.3], {} }})", png, common),
          fmt::format(R"({{ "mfp_mm": [0.8, 0.5, 0.3], {} }})", common),
          fmt::format(R"({{ "mfp_mm": {}, {} }})", vec_json(glm::vec3(0.8f, 0.5f, 0.3f) * (51.0f / 255.0f)), common)};
}

void expect_references_follow_the_map(bool volpath, const SplitCase& split) {
  const Scene textured = sphere_scene(split.textured, split.scale_mm);
  const Scene uniform_left = sphere_scene(split.left, split.scale_mm);
  const Scene uniform_right = sphere_scene(split.right, split.scale_mm);
  const int samples = volpath ? 6000 : 4000;
  double largest_z = 0.0;  // the other half's material, in paired standard errors, at the point it differs most
  for (double u : {0.25, 0.75}) {
    const double tex_u = texture_u_of(textured, u);
    ASSERT_TRUE(std::abs(tex_u - 0.25) < 0.1 || std::abs(tex_u - 0.75) < 0.1) << tex_u;
    const Scene& same = tex_u < 0.5 ? uniform_left : uniform_right;
    const Scene& other = tex_u < 0.5 ? uniform_right : uniform_left;
    std::vector<double> a, b, c;
    const reference::Estimate t = sphere_radiance(textured, volpath, u, samples, &a);
    const reference::Estimate s = sphere_radiance(same, volpath, u, samples, &b);
    const reference::Estimate o = sphere_radiance(other, volpath, u, samples, &c);
    ASSERT_EQ(a.size(), b.size());
    reference::Accumulator diff, diff_other;
    for (std::size_t i = 0; i < a.size(); ++i) diff.add(a[i] - b[i]), diff_other.add(a[i] - c[i]);
    const reference::Estimate d = diff.estimate(), e = diff_other.estimate();
    std::printf("%s, %s, u %.2f (texture u %.3f): textured %.5f +- %.5f, untextured same half %.5f (paired "
                "difference %.2e +- %.2e), other half %.5f (%.2e +- %.2e)\n",
                volpath ? "volpath" : "bssrdf", split.name, u, tex_u, t.mean, t.standard_error, s.mean, d.mean,
                d.standard_error, o.mean, e.mean, e.standard_error);
    // Equal to the untextured material of the texel's half: within the inversion's precision (2e-3 of the
    // mean) plus 4 paired standard errors (volpath's paths can branch apart on a 1e-4 change of sigma_t).
    EXPECT_LT(std::abs(d.mean), 2e-3 * s.mean + 4.0 * d.standard_error);
    largest_z = std::max(largest_z, std::abs(e.mean) / e.standard_error);
  }
  // And far from the other half's material where it matters: the map made the difference. (A 5x shorter mean free
  // path at the same surface albedo changes little where the surface is lit head-on: 2 standard errors at u 0.25.)
  EXPECT_GT(largest_z, 6.0) << split.name;
}

TEST(MaterialMaps, BssrdfReferenceTakesTheCoefficientsWhereTheLightLeaves) {
  TempFile albedo(".albedo.png"), mfp(".mfp.png");
  expect_references_follow_the_map(false, albedo_split(albedo.path()));
  expect_references_follow_the_map(false, mfp_split(mfp.path()));
}

TEST(MaterialMaps, VolpathTakesTheMediumWhereTheCameraPathEnters) {
  TempFile albedo(".albedo.png"), mfp(".mfp.png");
  expect_references_follow_the_map(true, albedo_split(albedo.path()));
  expect_references_follow_the_map(true, mfp_split(mfp.path()));
}

TEST(MaterialMaps, ATexturedMaterialEditedAfterLoadingIsRefused) {
  TempFile png(".png");
  write_halves_png(png.path(), 4, 1, {200, 150, 120}, {150, 180, 230});
  const Scene loaded = sphere_scene(fmt::format(R"({{ "albedo_map": "{}", "mfp_mm": 1, "model": "standard" }})", png.path()));
  EXPECT_NO_THROW(check_material_maps(loaded));
  const std::string where = "maps-test: /objects/0/material";
  Scene edited = loaded;
  edited.objects[0].material->g = glm::vec3(0.5f);
  EXPECT_EQ(error_message([&] { reference::EmbreeScene rt(edited); }),
            where + ": the coefficients, g, eta and model of a textured material are those its albedo_map was made "
                    "with (its texels are inverted at load); change them in the scene file");
  edited = loaded;
  edited.objects[0].material->sigma_a *= 2.0f;
  EXPECT_NE(error_message([&] { check_material_maps(edited); }), "");
  edited = loaded;
  edited.objects[0].material->model = BssrdfModel::Tabulated;
  EXPECT_EQ(error_message([&] { check_material_maps(edited); }),
            where + "/model: tabulated takes no albedo_map: its tables hold one medium each, a texture has a medium "
                    "per texel");
  edited = loaded;
  edited.objects[0].mesh.uvs.clear();
  EXPECT_EQ(error_message([&] { check_material_maps(edited); }),
            where + "/albedo_map: a texture needs the mesh's texture coordinates; the shape has none");
}

TEST(MaterialMaps, VolpathReferencesKeepTheModelWhenItSetsTheCoefficients) {
  // A material given by its surface albedo is the model's inversion: another model is another medium, so a cached
  // volpath reference of one model must not stand for another. A preset's coefficients do not depend on it.
  TempFile by_albedo(".albedo.json"), by_preset(".preset.json");
  {
    std::ofstream(by_albedo.path()) << R"({ "objects": [{ "shape": "sphere", "material": { "albedo": 0.8, "mfp_mm": 1 } }] })";
    std::ofstream(by_preset.path()) << R"({ "objects": [{ "shape": "sphere", "material": "Marble" }] })";
  }
  const std::vector<std::string> sets = {"objects.0.material.model=\"standard\"", "render.width=32"};
  EXPECT_EQ(reference::relevant_overrides(sets, "volpath", by_albedo.path()).size(), 2u);
  EXPECT_EQ(reference::relevant_overrides(sets, "volpath", by_preset.path()).size(), 1u);
  EXPECT_EQ(reference::relevant_overrides(sets, "bssrdf", by_preset.path()).size(), 2u);
  EXPECT_NE(reference::reference_key(by_albedo.path(), sets, "volpath"),
            reference::reference_key(by_albedo.path(), {"render.width=32"}, "volpath"));
  EXPECT_EQ(reference::reference_key(by_preset.path(), sets, "volpath"),
            reference::reference_key(by_preset.path(), {"render.width=32"}, "volpath"));
}

}  // namespace
}  // namespace lucent
