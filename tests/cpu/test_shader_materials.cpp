// test_shader_materials.cpp: Blender 3.4 and Blender 4 (Principled v2) Principled and OpenPBR subsurface inputs
// as lucent materials
// (materials/principled_subsurface.h, materials/openpbr_subsurface.h, materials/shader_material_json.h), the
// advice that names the models reaching an out-of-range albedo, and the objects' up_axis.
//
// Expected values: the Principled case below was computed by a separate Python script from the formulas in
// docs/materials.md (bisection to 1e-30 on Jensen's R_d, double precision); the OpenPBR round trip by the model's
// flat total of the converted material (an independent forward evaluation); the Blender 4 case likewise, by a
// separate Python script from Cycles 4.x's formulas (below); the fit of Wrenninge et al. against
// van de Hulst's independent formula for the same index-matched half-space; up_axis against a hand-computed vertex.
#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli_runner.h"
#include "../test_paths.h"
#include "../test_support.h"
#include "lucent/image.h"
#include "lucent/scene.h"
#include "materials/artist_parameters.h"
#include "materials/model_total_reflectance.h"
#include "materials/openpbr_subsurface.h"
#include "materials/principled_subsurface.h"

namespace lucent {
namespace {

using nlohmann::json;

Scene shader_test_scene(const json& material, double scale_mm) {
  const json scene = {{"scale_mm", scale_mm},
                      {"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
                      {"objects", json::array({json{{"shape", "sphere"}, {"material", material}}})}};
  return parse_scene(scene.dump(), "s.json", ".");
}

std::string shader_test_error(const json& material) {
  return test::error_message([&] { shader_test_scene(material, 1.0); });
}

// base (0.8, 0.8, 0.8), subsurface 0.5, colour (0.9, 0.5, 0.2), radius (2, 1, 0.5) units at 10 mm/unit, IOR 1.4,
// anisotropy 0.3, random_walk: A = (0.85, 0.65, 0.5); the script's alpha', radius, alpha and coefficients.
constexpr double kExpectedAlphaPrime[3] = {0.999060005, 0.992495556, 0.977629564};
constexpr double kExpectedRadiusMm[3] = {0.5310354, 0.75022218, 0.647646262};
constexpr double kExpectedAlpha[3] = {0.996930188, 0.975518345, 0.937317591};
constexpr double kExpectedSigmaS[3] = {2.68190404, 1.85757989, 2.06752545};
constexpr double kExpectedSigmaA[3] = {0.00825829179, 0.0466179137, 0.138264209};

PrincipledSubsurface principled_case() {
  PrincipledSubsurface p;
  p.base_color = glm::vec3(0.8f);
  p.subsurface = 0.5f;
  p.subsurface_color = {0.9f, 0.5f, 0.2f};
  p.subsurface_radius = {2.0f, 1.0f, 0.5f};
  p.subsurface_ior = 1.4f;
  p.subsurface_anisotropy = 0.3f;
  return p;
}

TEST(PrincipledSubsurface, RandomWalkMatchesTheFormulas) {
  const PrincipledConversion c = principled_subsurface_material(principled_case(), 10.0, "test");
  for (int b = 0; b < 3; ++b) {
    EXPECT_NEAR(c.alpha_prime[b], kExpectedAlphaPrime[b], 1e-8) << "band " << b;
    EXPECT_NEAR(c.radius_mm[b], kExpectedRadiusMm[b], 1e-6 * kExpectedRadiusMm[b]) << "band " << b;
    EXPECT_NEAR(c.alpha[b], kExpectedAlpha[b], 1e-8) << "band " << b;
    EXPECT_NEAR(c.material.sigma_s[b], kExpectedSigmaS[b], 1e-5 * kExpectedSigmaS[b]) << "band " << b;
    EXPECT_NEAR(c.material.sigma_a[b], kExpectedSigmaA[b], 1e-4 * kExpectedSigmaA[b]) << "band " << b;
  }
  EXPECT_EQ(c.material.g, glm::vec3(0.3f));
  EXPECT_EQ(c.material.eta, 1.0f);  // Cycles' walk has no refractive boundary
}

// Cycles' "radius" under random_walk is the diffusion length of its own dipole: 1 / (sigma_t' sqrt(3 (1 - alpha')))
// = subsurface_radius * subsurface * scale_mm, with sigma_t' = sigma_t (1 - g).
TEST(PrincipledSubsurface, RandomWalkRadiusIsTheDiffusionLength) {
  const PrincipledSubsurface p = principled_case();
  const PrincipledConversion c = principled_subsurface_material(p, 10.0, "test");
  for (int b = 0; b < 3; ++b) {
    const double sigma_t_prime = (double(c.material.sigma_a[b]) + c.material.sigma_s[b]) * (1.0 - 0.3);
    const double diffusion_length = 1.0 / (sigma_t_prime * std::sqrt(3.0 * (1.0 - c.alpha_prime[b])));
    EXPECT_NEAR(diffusion_length, p.subsurface_radius[b] * 0.5 * 10.0, 1e-5 * p.subsurface_radius[b] * 5.0);
  }
}

TEST(PrincipledSubsurface, FixedRadiusScalesByOneOverFourPi) {
  PrincipledSubsurface p = principled_case();
  p.method = PrincipledMethod::RandomWalkFixedRadius;
  const PrincipledConversion c = principled_subsurface_material(p, 10.0, "test");
  for (int b = 0; b < 3; ++b) {
    const double sigma_t_prime = (double(c.material.sigma_a[b]) + c.material.sigma_s[b]) * (1.0 - 0.3);
    EXPECT_NEAR(1.0 / sigma_t_prime, p.subsurface_radius[b] * 5.0 / (4.0 * M_PI), 1e-6 * p.subsurface_radius[b]);
  }
}

// Jensen's R_d inverted: R_d(alpha'(R)) = R inside Cycles' ends; R_d(1) = 1 (no absorption, all light returns).
TEST(PrincipledSubsurface, DipoleInversionRoundTrip) {
  EXPECT_NEAR(cycles_dipole_rd(1.0, 1.4), 1.0, 1e-12);
  for (double rd : {0.001, 0.05, 0.3, 0.6, 0.9, 0.99})
    for (double eta : {1.01, 1.4, 2.0}) EXPECT_NEAR(cycles_dipole_rd(cycles_alpha_prime(rd, eta), eta), rd, 1e-9);
  EXPECT_EQ(cycles_alpha_prime(5e-5, 1.4), 0.0);
  EXPECT_EQ(cycles_alpha_prime(0.995, 1.4), 0.999999);
}

// The fit of Wrenninge et al. and van de Hulst's formula describe the same index-matched half-space: within 0.01
// of each other over A in [0.1, 0.9] (at g 0 and 0.5; they differ by up to 0.006 there).
TEST(PrincipledSubsurface, AlbedoFitAgreesWithVanDeHulst) {
  for (double g : {0.0, 0.5})
    for (double a = 0.1; a <= 0.9001; a += 0.1)
      EXPECT_NEAR(cycles_single_scattering_albedo(a, g), van_de_hulst_single_scattering_albedo(a, g), 0.01)
          << "A " << a << " g " << g;
}

// van de Hulst's inversion against its forward formula C = (1 - s)(1 - 0.139 s) / (1 + 1.17 s),
// s = sqrt((1 - alpha) / (1 - alpha g)).
TEST(OpenPbrSubsurface, VanDeHulstInversionRoundTrip) {
  for (double g : {-0.3, 0.0, 0.8})
    for (double c : {0.05, 0.3, 0.6, 0.9}) {
      const double alpha = van_de_hulst_single_scattering_albedo(c, g);
      const double s = std::sqrt((1.0 - alpha) / (1.0 - alpha * g));
      EXPECT_NEAR((1.0 - s) * (1.0 - 0.139 * s) / (1.0 + 1.17 * s), c, 1e-4) << "C " << c << " g " << g;
    }
}

TEST(PrincipledSubsurface, SceneBlockUsesScaleMm) {
  const json block = {{"base_color", 0.8}, {"subsurface", 0.5}, {"subsurface_color", {0.9, 0.5, 0.2}},
                      {"subsurface_radius", {2, 1, 0.5}}, {"subsurface_ior", 1.4}, {"subsurface_anisotropy", 0.3}};
  const Scene scene = shader_test_scene({{"principled", block}, {"model", "directional"}}, 10.0);
  const Material& m = *scene.objects[0].material;
  for (int b = 0; b < 3; ++b) EXPECT_NEAR(m.sigma_s[b], kExpectedSigmaS[b], 1e-5 * kExpectedSigmaS[b]);
  EXPECT_EQ(m.model, BssrdfModel::DirectionalDipole);
}

TEST(PrincipledSubsurface, SceneBlockErrors) {
  EXPECT_EQ(shader_test_error({{"principled", {{"subsurface_method", "burley"}}}}),
            "s.json: /objects/0/material/principled/subsurface_method: burley: Cycles' Christensen-Burley profile "
            "has no medium to convert; use random_walk or random_walk_fixed_radius");
  EXPECT_EQ(shader_test_error({{"principled", {{"subsurface", 0}}}}),
            "s.json: /objects/0/material/principled: subsurface = 0 is out of range; allowed range (0, 1] (0 is an "
            "opaque diffuse surface: give the object an albedo instead)");
  EXPECT_EQ(shader_test_error({{"principled", {{"subsurface_color", 0}, {"base_color", {0.5, 0.5, 0.5}}}}}),
            "s.json: /objects/0/material/principled: the mixed colour (base_color and subsurface_color by subsurface) "
            "is 0 in band 0: a black medium does not scatter; give the object an albedo instead");
  const std::string unreached = shader_test_error({{"openpbr", {{"subsurface_color", {0.99, 0.5, 0.5}}}},
                                                   {"model", "photon-beam"}});
  EXPECT_EQ(unreached.rfind("s.json: /objects/0/material/openpbr (subsurface_color as albedo): albedo[0] = 0.99 is "
                            "above the largest flat total the model reaches", 0), 0u) << unreached;
  EXPECT_EQ(shader_test_error({{"principled", json::object()}, {"openpbr", json::object()}}),
            "s.json: /objects/0/material: give one of principled and openpbr");
  EXPECT_EQ(shader_test_error({{"openpbr", {{"subsurface_weight", 0.5}}}}),
            "s.json: /objects/0/material/openpbr: subsurface_weight = 0.5: lucent renders the subsurface slab alone "
            "(weight 1); a weight of 0 is an opaque object (give it an albedo)");
}

// OpenPBR's subsurface_color is the flat total per refracted power: the converted material's own flat total under
// its model is the colour, and its mean free path is radius * radius_scale * scale_mm.
TEST(OpenPbrSubsurface, FlatTotalIsTheColourAndMfpIsTheRadius) {
  const json block = {{"subsurface_color", {0.85, 0.6, 0.4}}, {"subsurface_radius", 0.3},
                      {"subsurface_radius_scale", {1, 0.5, 0.25}}, {"subsurface_scatter_anisotropy", 0.2},
                      {"specular_ior", 1.45}};
  for (const char* model : {"standard", "better-dipole"}) {
    const Scene scene = shader_test_scene({{"openpbr", block}, {"model", model}}, 10.0);
    const Material& m = *scene.objects[0].material;
    const glm::dvec3 total = model_total_reflectance(m, 0.0).total;
    const double colour[3] = {0.85, 0.6, 0.4}, mfp[3] = {3.0, 1.5, 0.75};
    for (int b = 0; b < 3; ++b) {
      EXPECT_NEAR(total[b], colour[b], 1e-3) << model << " band " << b;
      EXPECT_NEAR(1.0 / (double(m.sigma_a[b]) + m.sigma_s[b]), mfp[b], 1e-5 * mfp[b]) << model << " band " << b;
    }
    EXPECT_FLOAT_EQ(m.eta, 1.45f);
    EXPECT_EQ(m.g, glm::vec3(0.2f));
  }
}

// The message for an albedo a model does not reach names one that does, and that model inverts it.
TEST(ArtistAdvice, OutOfRangeAlbedoNamesAModelThatReachesIt) {
  const test::CliResult r = test::run_cli("materials invert --albedo 0.8,0.45,0.05 --mfp 1 --model directional");
  EXPECT_EQ(r.exit_code, 1);
  const FlatTotalRange directional = flat_total_range(BssrdfModel::DirectionalDipole, 0.0f, 1.3f);
  EXPECT_GT(directional.lowest, 0.05);
  EXPECT_EQ(r.output, fmt::format("lucent: materials invert: albedo[2] = 0.05 is below the smallest flat total the "
                                  "model reaches; allowed range ({:.4g}, 1) for the directional model at g 0 and eta "
                                  "1.3; the standard, photon-beam and better-dipole models reach it (model "
                                  "\"standard\")\n",
                                  directional.lowest));
  ArtistParameters a;
  a.albedo = {0.8f, 0.45f, 0.05f};
  a.model = BssrdfModel::StandardDipole;
  EXPECT_NEAR(model_total_reflectance(invert_artist_parameters(a, "test").material, 0.0).total.z, 0.05, 1e-3);
  // Nothing reaches 0.999 at eta 1.3 except the models whose totals reach 1.
  const std::vector<BssrdfModel> none = models_reaching(0.5, 1.0, glm::vec3(0.0f), 1.3f, BssrdfModel::StandardDipole);
  EXPECT_TRUE(none.empty());
}

// A map whose texels a model does not reach: the warning names the model that reaches them all.
TEST(ArtistAdvice, AlbedoMapWarningNamesAModel) {
  test::TempFile png(".png");
  ImageRGBA8 image{2, 1, std::vector<std::uint8_t>(8, 255)};
  image.at(0, 0)[0] = image.at(0, 0)[1] = image.at(0, 0)[2] = 63;   // sRGB 63: linear 0.0497
  image.at(1, 0)[0] = image.at(1, 0)[1] = image.at(1, 0)[2] = 188;  // sRGB 188: linear 0.503
  write_png(png.path(), image);
  const json scene = {
      {"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
      {"objects", json::array({json{{"shape", "sphere"},
                                    {"material", {{"albedo_map", png.path()}, {"mfp_mm", 1}, {"model", "directional"}}}}})}};
  ::testing::internal::CaptureStderr();
  parse_scene(scene.dump(), "s.json", ".");
  const std::string warning = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(warning.find("3 of 6 texel values are outside the surface albedos the directional model reaches"),
            std::string::npos) << warning;
  EXPECT_NE(warning.find("(the map spans [0.04971, 0.5029]); clamped to them; the standard, photon-beam and "
                         "better-dipole models reach them all (model \"standard\")"),
            std::string::npos) << warning;
  const FlatTotalRange standard = flat_total_range(BssrdfModel::StandardDipole, 0.0f, 1.3f);
  EXPECT_TRUE(standard.contains(0.0497) && standard.contains(0.5029));
  // A black texel is outside every model's range: the model that clamps the fewest values is named, here the
  // black texel's three (the standard dipole reaches 0.0497, the directional dipole neither).
  image.at(1, 0)[0] = image.at(1, 0)[1] = image.at(1, 0)[2] = 0;
  write_png(png.path(), image);
  ::testing::internal::CaptureStderr();
  parse_scene(scene.dump(), "s.json", ".");
  const std::string black = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(black.find("6 of 6 texel values are outside the surface albedos the directional model reaches"),
            std::string::npos) << black;
  EXPECT_NE(black.find("; the standard model clamps the fewest, 3 (model \"standard\"); texel values of 0 (no light "
                       "returns) and 1 (no absorption) are outside every model's range"),
            std::string::npos) << black;
}

// up_axis z turns (x, y, z) into (x, z, -y) before scale, rotation and translation: (1, 2, 3) -> (1, 3, -2),
// scaled by 2 -> (2, 6, -4), turned 90 degrees about y ((x, z) -> (z, -x)) -> (-4, 6, -2), moved by (1, 0, 0).
TEST(UpAxis, ZUpVertexByHand) {
  const json scene = {{"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
                      {"objects", json::array({json{{"shape", "sphere"}, {"up_axis", "z"}, {"scale", 2},
                                                    {"rotate_deg", {0, 90, 0}}, {"translate", {1, 0, 0}}}})}};
  const Scene s = parse_scene(scene.dump(), "s.json", ".");
  const glm::vec3 p = glm::vec3(s.objects[0].world_from_object * glm::vec4(1.0f, 2.0f, 3.0f, 1.0f));
  EXPECT_NEAR(p.x, -3.0f, 1e-5f);
  EXPECT_NEAR(p.y, 6.0f, 1e-5f);
  EXPECT_NEAR(p.z, -2.0f, 1e-5f);
  // A mesh's +z (Blender's up) becomes +y.
  json y_up = scene;
  y_up["objects"][0].erase("scale"), y_up["objects"][0].erase("rotate_deg"), y_up["objects"][0].erase("translate");
  const glm::vec3 up = glm::vec3(parse_scene(y_up.dump(), "s.json", ".").objects[0].world_from_object *
                                 glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));
  EXPECT_NEAR(glm::distance(up, glm::vec3(0.0f, 1.0f, 0.0f)), 0.0f, 1e-6f);
  y_up["objects"][0]["up_axis"] = "x";
  const glm::vec3 x_up = glm::vec3(parse_scene(y_up.dump(), "s.json", ".").objects[0].world_from_object *
                                   glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
  EXPECT_NEAR(glm::distance(x_up, glm::vec3(0.0f, 1.0f, 0.0f)), 0.0f, 1e-6f);
}

// The scene tools/blender/example_scene.py built and export_lucent.py wrote (Blender 3.4.1): the floor plane at
// Blender z = -0.006 m lies at lucent y = -0.006; the sphere of radius 0.006 m about the origin; Blender's camera
// at (0, -0.05, 0) looking along +y is at (0, 0, 0.05) looking along -z; the point light at (0.03, -0.03, 0.03) is
// at (0.03, 0.03, 0.03); scale_mm 1000; the principled block becomes the same material as the library's conversion.
TEST(BlenderExport, ExampleSceneInLucentsFrame) {
  const Scene s = load_scene(std::string(LUCENT_SOURCE_DIR) + "/tools/blender/example/example.json");
  EXPECT_EQ(s.scale_mm, 1000.0f);
  ASSERT_EQ(s.objects.size(), 2u);
  auto world_bounds = [](const SceneObject& o, glm::vec3& lo, glm::vec3& hi) {
    lo = glm::vec3(1e30f), hi = glm::vec3(-1e30f);
    for (const glm::vec3& p : o.mesh.positions) {
      const glm::vec3 w = glm::vec3(o.world_from_object * glm::vec4(p, 1.0f));
      lo = glm::min(lo, w), hi = glm::max(hi, w);
    }
  };
  glm::vec3 lo, hi;
  world_bounds(s.objects[1], lo, hi);
  EXPECT_NEAR(lo.y, -0.006f, 1e-6f);
  EXPECT_NEAR(hi.y, -0.006f, 1e-6f);
  world_bounds(s.objects[0], lo, hi);
  EXPECT_NEAR(hi.y, 0.006f, 1e-5f);
  EXPECT_NEAR(lo.y, -0.006f, 1e-5f);
  EXPECT_NEAR(glm::distance(s.camera.eye, glm::vec3(0.0f, 0.0f, 0.05f)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(glm::normalize(s.camera.target - s.camera.eye), glm::vec3(0.0f, 0.0f, -1.0f)), 1.0f, 1e-6f);
  ASSERT_EQ(s.point_lights.size(), 1u);
  EXPECT_NEAR(glm::distance(s.point_lights[0].position, glm::vec3(0.03f)), 0.0f, 1e-6f);
  EXPECT_NEAR(s.point_lights[0].intensity.x, 2.0 / (4.0 * M_PI), 1e-6);  // 2 W point light
  PrincipledSubsurface p;
  p.base_color = glm::vec3(0.8f);
  p.subsurface = 1.0f;
  p.subsurface_radius = {0.003f, 0.0015f, 0.0008f};
  p.subsurface_color = {0.85f, 0.6f, 0.4f};
  const Material expected = principled_subsurface_material(p, 1000.0, "test").material;
  EXPECT_EQ(s.objects[0].material->sigma_s, expected.sigma_s);
  EXPECT_EQ(s.objects[0].material->sigma_a, expected.sigma_a);
  EXPECT_EQ(s.objects[0].material->name, "skin");
  EXPECT_FALSE(s.objects[1].material.has_value());
}

// Blender 4's Principled BSDF (v2), with Cycles 4.x's formulas: svm/closure.h (svm_node_closure_bsdf, Principled
// case): radius = max(Subsurface Radius * Subsurface Scale, 0), albedo = Base Color clamped to [0, 1], ior = IOR
// (Subsurface IOR under random_walk_skin), g = Subsurface Anisotropy; closure/bssrdf.h (bssrdf_setup): ior clamped
// to [1.01, 3.8], g to [0, 0.9]; bssrdf_setup_radius: random_walk d *= 1 / (4 pi), random_walk_skin
// d *= sqrt(3 (1 - alpha')) with alpha' solving Jensen's R_d(alpha') = A at the ior;
// integrator/subsurface_random_walk.h (subsurface_random_walk_remap): sigma_t = 1 / (d (1 - g)), alpha from the
// Wrenninge-Villemin-Hery fit at A and g.
//
// The case: base (0.85, 0.6, 0.4), weight 1, radius (1, 0.5, 0.25) x scale 0.004 m = (4, 2, 1) mm at scale_mm 1000,
// IOR 1.5, Subsurface IOR 1.4, anisotropy 0.3. Computed with /usr/bin/python3 from those formulas (double precision,
// bisection to convergence; not lucent's code):
//   eta 1.4: F_dr = -1.44/1.96 + 0.71/1.4 + 0.668 + 0.0636 * 1.4 = 0.52949, 4/3 A_F = 4/3 * 1.52949 / 0.47051 = 4.3343
//   random_walk_skin: alpha' = (0.999060005, 0.989000215, 0.955632533)
//     d = (4, 2, 1) mm * sqrt(3 (1 - alpha')) = (0.21241416, 0.363314488, 0.364832018) mm
//   alpha(A, 0.3) = (0.996930188, 0.965662742, 0.892002218) (both methods: the same A and g)
//   sigma_t = 1 / (0.7 d) = (6.72540583, 3.93205193, 3.91569643) mm^-1
//     sigma_s = alpha sigma_t = (6.7047601, 3.79703604, 3.4928099), sigma_a = (0.0206457295, 0.135015879, 0.422886529)
//   random_walk: d = (4, 2, 1) mm / (4 pi) = (0.318309886, 0.159154943, 0.0795774715) mm (IOR not used)
//     sigma_s = (4.47421222, 8.66776851, 16.0131864), sigma_a = (0.0137772827, 0.308210503, 1.93877165)
// Tolerance 1e-5 relative (the inputs are floats: 0.004f is 0.004 (1 + 5e-8); the coefficients are stored as floats).
constexpr double kV2SkinAlphaPrime[3] = {0.999060005, 0.989000215, 0.955632533};
constexpr double kV2SkinRadiusMm[3] = {0.21241416, 0.363314488, 0.364832018};
constexpr double kV2Alpha[3] = {0.996930188, 0.965662742, 0.892002218};
constexpr double kV2SkinSigmaS[3] = {6.7047601, 3.79703604, 3.4928099};
constexpr double kV2SkinSigmaA[3] = {0.0206457295, 0.135015879, 0.422886529};
constexpr double kV2WalkRadiusMm[3] = {0.318309886, 0.159154943, 0.0795774715};
constexpr double kV2WalkSigmaS[3] = {4.47421222, 8.66776851, 16.0131864};
constexpr double kV2WalkSigmaA[3] = {0.0137772827, 0.308210503, 1.93877165};

json principled_v2_block(const char* method) {
  return {{"base_color", {0.85, 0.6, 0.4}}, {"subsurface_weight", 1}, {"subsurface_radius", {1, 0.5, 0.25}},
          {"subsurface_scale", 0.004}, {"ior", 1.5}, {"subsurface_ior", 1.4}, {"subsurface_anisotropy", 0.3},
          {"subsurface_method", method}};
}

TEST(PrincipledV2, RandomWalkSkinMatchesCycles4Formulas) {
  PrincipledV2Subsurface p;
  p.base_color = {0.85f, 0.6f, 0.4f};
  p.subsurface_radius = {1.0f, 0.5f, 0.25f};
  p.subsurface_scale = 0.004f;
  p.ior = 1.5f;
  p.subsurface_ior = 1.4f;
  p.subsurface_anisotropy = 0.3f;
  p.method = PrincipledV2Method::RandomWalkSkin;
  const PrincipledConversion c = principled_v2_subsurface_material(p, 1000.0, "test");
  const Scene scene = shader_test_scene({{"principled", principled_v2_block("random_walk_skin")}}, 1000.0);
  const Material& m = *scene.objects[0].material;
  for (int b = 0; b < 3; ++b) {
    EXPECT_NEAR(c.alpha_prime[b], kV2SkinAlphaPrime[b], 1e-6) << "band " << b;
    EXPECT_NEAR(c.radius_mm[b], kV2SkinRadiusMm[b], 1e-5 * kV2SkinRadiusMm[b]) << "band " << b;
    EXPECT_NEAR(c.alpha[b], kV2Alpha[b], 1e-6) << "band " << b;
    EXPECT_NEAR(m.sigma_s[b], kV2SkinSigmaS[b], 1e-5 * kV2SkinSigmaS[b]) << "band " << b;
    EXPECT_NEAR(m.sigma_a[b], kV2SkinSigmaA[b], 1e-5 * kV2SkinSigmaA[b]) << "band " << b;
  }
  EXPECT_EQ(m.g, glm::vec3(0.3f));
  EXPECT_EQ(m.eta, 1.0f);  // Cycles 4's walk leaves where it first crosses the surface, as 3.4's
}

TEST(PrincipledV2, RandomWalkUsesTheRadiusAsGiven) {
  const Scene scene = shader_test_scene({{"principled", principled_v2_block("random_walk")}}, 1000.0);
  const Material& m = *scene.objects[0].material;
  for (int b = 0; b < 3; ++b) {
    const double sigma_t_prime = (double(m.sigma_a[b]) + m.sigma_s[b]) * (1.0 - 0.3);
    EXPECT_NEAR(1.0 / sigma_t_prime, kV2WalkRadiusMm[b], 1e-5 * kV2WalkRadiusMm[b]) << "band " << b;
    EXPECT_NEAR(m.sigma_s[b], kV2WalkSigmaS[b], 1e-5 * kV2WalkSigmaS[b]) << "band " << b;
    EXPECT_NEAR(m.sigma_a[b], kV2WalkSigmaA[b], 1e-5 * kV2WalkSigmaA[b]) << "band " << b;
    EXPECT_NEAR(m.sigma_s[b] / (double(m.sigma_a[b]) + m.sigma_s[b]), kV2Alpha[b], 1e-6) << "band " << b;
  }
  // The main IOR only bends random_walk's entry: another IOR, the same medium.
  json other_ior = principled_v2_block("random_walk");
  other_ior["ior"] = 2.5;
  const Material m2 = *shader_test_scene({{"principled", other_ior}}, 1000.0).objects[0].material;
  EXPECT_EQ(m2.sigma_s, m.sigma_s);
  EXPECT_EQ(m2.sigma_a, m.sigma_a);
}

// One look in both versions' inputs: Blender 3.4's subsurface 1, subsurface_color C, radius r, subsurface_ior n is
// Blender 4's weight 1, base_color C, radius r / s at scale s, with Blender 3's random_walk renamed random_walk_skin
// (Subsurface IOR n) and random_walk_fixed_radius renamed random_walk. Relative 1e-6 (r / s * s in floats).
TEST(PrincipledV2, SameLookAsBlender3Inputs) {
  const json v1_walk = {{"base_color", 0.3}, {"subsurface", 1}, {"subsurface_color", {0.9, 0.5, 0.2}},
                        {"subsurface_radius", {0.004, 0.002, 0.001}}, {"subsurface_ior", 1.3},
                        {"subsurface_anisotropy", 0.5}};
  const json v2_skin = {{"base_color", {0.9, 0.5, 0.2}}, {"subsurface_weight", 1},
                        {"subsurface_radius", {0.08, 0.04, 0.02}}, {"subsurface_scale", 0.05}, {"ior", 1.45},
                        {"subsurface_ior", 1.3}, {"subsurface_anisotropy", 0.5}, {"subsurface_method", "random_walk_skin"}};
  json v1_fixed = v1_walk;
  v1_fixed["subsurface_method"] = "random_walk_fixed_radius";
  json v2_walk = v2_skin;
  v2_walk["subsurface_method"] = "random_walk";
  json v2_explicit = {{"version", 4}, {"base_color", {0.9, 0.5, 0.2}}, {"subsurface_radius", {0.08, 0.04, 0.02}},
                      {"subsurface_scale", 0.05}, {"subsurface_anisotropy", 0.5}};  // weight 1 by default
  const std::pair<json, json> pairs[] = {{v1_walk, v2_skin}, {v1_fixed, v2_walk}, {v1_fixed, v2_explicit}};
  for (const auto& [v1, v2] : pairs) {
    const Material a = *shader_test_scene({{"principled", v1}}, 1000.0).objects[0].material;
    const Material b = *shader_test_scene({{"principled", v2}}, 1000.0).objects[0].material;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(b.sigma_s[k], a.sigma_s[k], 1e-6 * a.sigma_s[k]) << v2.dump() << " band " << k;
      EXPECT_NEAR(b.sigma_a[k], a.sigma_a[k], 1e-6 * a.sigma_a[k]) << v2.dump() << " band " << k;
    }
    EXPECT_EQ(b.g, a.g);
    EXPECT_EQ(b.eta, a.eta);
  }
  // Blender 3's random_walk and Blender 4's random_walk (a different radius scaling under one name) differ.
  const Material v3 = *shader_test_scene({{"principled", v1_walk}}, 1000.0).objects[0].material;
  const Material v4 = *shader_test_scene({{"principled", v2_walk}}, 1000.0).objects[0].material;
  EXPECT_GT(std::abs(v4.sigma_s[0] / v3.sigma_s[0] - 1.0f), 0.1f);
}

TEST(PrincipledV2, SceneBlockErrors) {
  EXPECT_EQ(shader_test_error({{"principled", {{"subsurface", 1}, {"subsurface_color", 0.5}, {"subsurface_scale", 0.1},
                                               {"subsurface_method", "random_walk_skin"}}}}),
            "s.json: /objects/0/material/principled: Blender 3's keys (subsurface, subsurface_color) and Blender 4's "
            "keys (subsurface_scale, subsurface_method \"random_walk_skin\") in one block; give one version's inputs");
  EXPECT_EQ(shader_test_error({{"principled", {{"version", 3}, {"subsurface_weight", 1}}}}),
            "s.json: /objects/0/material/principled/version: 3 (Blender 3.4's Principled BSDF) with Blender 4's keys "
            "(subsurface_weight); give one version's inputs");
  EXPECT_EQ(shader_test_error({{"principled", {{"version", 4}, {"subsurface_method", "random_walk_fixed_radius"}}}}),
            "s.json: /objects/0/material/principled/version: 4 (Blender 4's Principled BSDF) with Blender 3's keys "
            "(subsurface_method \"random_walk_fixed_radius\"); give one version's inputs");
  EXPECT_EQ(shader_test_error({{"principled", {{"subsurface_weight", 1.5}}}}),
            "s.json: /objects/0/material/principled/subsurface_weight: 1.5 is out of range; allowed range [0, 1]");
  EXPECT_EQ(shader_test_error({{"principled", {{"subsurface_weight", 1}, {"subsurface_scale", -0.1}}}}),
            "s.json: /objects/0/material/principled/subsurface_scale: -0.1 is out of range; allowed range [0, 1e+30] "
            "units");
  EXPECT_EQ(shader_test_error({{"principled", {{"subsurface_weight", 0.5}}}}),
            "s.json: /objects/0/material/principled: subsurface_weight = 0.5: Blender 4 mixes a diffuse surface "
            "(1 - weight) with the subsurface medium (weight); lucent renders the medium alone (weight 1); a weight "
            "of 0 is an opaque object (give it an albedo)");
  EXPECT_EQ(shader_test_error({{"principled", {{"subsurface_weight", 1}, {"subsurface_scale", 0}}}}),
            "s.json: /objects/0/material/principled: subsurface_scale = 0 is out of range; allowed range (0, inf) "
            "scene units (0 is an opaque diffuse surface: give the object an albedo instead)");
  EXPECT_EQ(shader_test_error({{"principled", {{"version", 4}, {"subsurface_method", "burley"}}}}),
            "s.json: /objects/0/material/principled/subsurface_method: burley: Cycles' Christensen-Burley profile "
            "has no medium to convert; use random_walk or random_walk_skin");
}

}  // namespace
}  // namespace lucent
