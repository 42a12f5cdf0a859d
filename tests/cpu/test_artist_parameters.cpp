// test_artist_parameters.cpp: coefficients from the surface albedo and the mean free path
// (materials/artist_parameters.h). The round trip is checked by an independent forward evaluation: the model's flat
// total of the inverted material itself (its own sigma_t per band, not the unit-sigma_t curve the search used),
// against the albedo asked for, within 1e-3. Bad input gets its exact one-line message, in the library, the scene
// loader and the CLI.
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli_runner.h"
#include "../test_support.h"
#include "lucent/error.h"
#include "lucent/scene.h"
#include "materials/artist_parameters.h"
#include "materials/model_total_reflectance.h"

namespace lucent {
namespace {

using nlohmann::json;

constexpr double kRoundTripTolerance = 1e-3;

struct InversionCase {
  BssrdfModel model;
  glm::vec3 albedo;
  float g, eta;
};

// Albedos 0.05 to 0.95 inside the range each model reaches (docs/materials.md): photon beam diffusion stays below
// 0.94-0.96; the directional dipole's total does not fall below 0.21 at eta 1, 0.14 at 1.3, 0.10 at 1.5.
const InversionCase kCases[] = {
    {BssrdfModel::StandardDipole, {0.05f, 0.5f, 0.95f}, 0.0f, 1.0f},
    {BssrdfModel::StandardDipole, {0.1f, 0.6f, 0.9f}, 0.8f, 1.3f},
    {BssrdfModel::StandardDipole, {0.3f, 0.7f, 0.85f}, -0.3f, 1.5f},
    {BssrdfModel::DirectionalDipole, {0.3f, 0.6f, 0.95f}, 0.0f, 1.0f},
    {BssrdfModel::DirectionalDipole, {0.2f, 0.5f, 0.9f}, 0.8f, 1.3f},
    {BssrdfModel::DirectionalDipole, {0.15f, 0.4f, 0.8f}, -0.3f, 1.5f},
    {BssrdfModel::PhotonBeamDiffusion, {0.05f, 0.4f, 0.8f}, 0.0f, 1.0f},
    {BssrdfModel::PhotonBeamDiffusion, {0.05f, 0.3f, 0.7f}, 0.8f, 1.3f},
    {BssrdfModel::BetterDipole, {0.05f, 0.5f, 0.85f}, 0.0f, 1.0f},
    {BssrdfModel::BetterDipole, {0.08f, 0.35f, 0.75f}, -0.3f, 1.5f},
};

ArtistParameters artist(const InversionCase& c) {
  ArtistParameters a;
  a.albedo = c.albedo;
  a.mfp_mm = {2.0f, 0.7f, 0.05f};
  a.g = glm::vec3(c.g);
  a.eta = c.eta;
  a.model = c.model;
  return a;
}

TEST(ArtistParameters, FlatTotalOfTheInvertedMaterialIsTheAlbedo) {
  for (const InversionCase& c : kCases) {
    const ArtistInversion inv = invert_artist_parameters(artist(c), "test");
    const glm::dvec3 total = model_total_reflectance(inv.material, 0.0).total;
    for (int b = 0; b < 3; ++b) {
      EXPECT_NEAR(total[b], c.albedo[b], kRoundTripTolerance)
          << to_string(c.model) << " g " << c.g << " eta " << c.eta << " band " << b;
      EXPECT_NEAR(1.0 / (inv.material.sigma_a[b] + inv.material.sigma_s[b]), artist(c).mfp_mm[b],
                  1e-6 * artist(c).mfp_mm[b]);
    }
    EXPECT_EQ(inv.material.g, glm::vec3(c.g));
    EXPECT_EQ(inv.material.eta, c.eta);
    EXPECT_EQ(inv.material.model, c.model);
  }
}

// The tabulated model (photon-transport tables, seconds per band) is inverted with the standard dipole's curve.
TEST(ArtistParameters, TabulatedModelUsesTheStandardDipoleCurve) {
  ArtistParameters a = artist(kCases[1]);
  const ArtistInversion standard = invert_artist_parameters(a, "test");
  a.model = BssrdfModel::Tabulated;
  const ArtistInversion tabulated = invert_artist_parameters(a, "test");
  EXPECT_EQ(tabulated.curve_model, BssrdfModel::StandardDipole);
  EXPECT_EQ(tabulated.material.model, BssrdfModel::Tabulated);
  EXPECT_EQ(tabulated.material.sigma_a, standard.material.sigma_a);
  EXPECT_EQ(tabulated.material.sigma_s, standard.material.sigma_s);
}

std::string inversion_error(const ArtistParameters& a) {
  return test::error_message([&] { invert_artist_parameters(a, "mat"); });
}

TEST(ArtistParameters, BadInputNamesTheParameter) {
  ArtistParameters a = artist(kCases[0]);
  a.albedo.x = 0.0f;
  EXPECT_EQ(inversion_error(a), "mat: albedo[0] = 0 is out of range; allowed range (0, 1)");
  a.albedo.x = 1.0f;
  EXPECT_EQ(inversion_error(a), "mat: albedo[0] = 1 is out of range; allowed range (0, 1)");
  a = artist(kCases[0]);
  a.albedo.y = std::nanf("");
  EXPECT_EQ(inversion_error(a), "mat: albedo[1] is NaN; allowed range (0, 1)");
  a = artist(kCases[0]);
  a.mfp_mm.z = 0.0f;
  EXPECT_EQ(inversion_error(a), "mat: mfp_mm[2] = 0 is out of range; allowed range (0, inf) mm");
  a.mfp_mm.z = -1.0f;
  EXPECT_EQ(inversion_error(a), "mat: mfp_mm[2] = -1 is out of range; allowed range (0, inf) mm");
  a.mfp_mm.z = HUGE_VALF;
  EXPECT_EQ(inversion_error(a), "mat: mfp_mm[2] = inf is out of range; allowed range (0, inf) mm");
  a = artist(kCases[0]);
  a.g = glm::vec3(1.0f);
  EXPECT_EQ(inversion_error(a), "mat: g[0] = 1 is out of range; allowed range (-1, 1)");
  a = artist(kCases[0]);
  a.eta = 0.5f;
  EXPECT_EQ(inversion_error(a), "mat: eta = 0.5 is out of range; allowed range [1, 3]");
}

// An albedo beyond the totals the model reaches: the message states the reachable range, and an independent
// forward evaluation at the search's end confirms the albedo is out of reach.
TEST(ArtistParameters, AlbedoBeyondTheModelsRange) {
  ArtistParameters a = artist(kCases[0]);
  a.model = BssrdfModel::PhotonBeamDiffusion;
  a.eta = 1.3f;
  a.albedo = {0.5f, 0.97f, 0.5f};
  const double lo = flat_total_of_albedo(a.model, kArtistAlphaMin, 0.0f, 1.3f);
  const double hi = flat_total_of_albedo(a.model, kArtistAlphaMax, 0.0f, 1.3f);
  Material near_one;
  near_one.sigma_a = glm::vec3(1e-7f);
  near_one.sigma_s = glm::vec3(1.0f);
  near_one.eta = 1.3f;
  near_one.model = a.model;
  EXPECT_LT(model_total_reflectance(near_one, 0.0).total.x, 0.97);
  EXPECT_EQ(inversion_error(a),
            fmt::format("mat: albedo[1] = 0.97 is above the largest flat total the model reaches; allowed range "
                        "({:.4g}, {:.4g}) for the photon-beam model at g 0 and eta 1.3; {}", lo, hi,
                        models_reaching_advice(0.97, 0.97, glm::vec3(0.0f), 1.3f, a.model)));
  a.model = BssrdfModel::DirectionalDipole;
  a.eta = 1.0f;
  a.albedo = {0.5f, 0.5f, 0.01f};
  const double directional_lo = flat_total_of_albedo(a.model, kArtistAlphaMin, 0.0f, 1.0f);
  EXPECT_GT(directional_lo, 0.01);
  EXPECT_EQ(inversion_error(a),
            fmt::format("mat: albedo[2] = 0.01 is below the smallest flat total the model reaches; allowed range "
                        "({:.4g}, 1) for the directional model at g 0 and eta 1; {}", directional_lo,
                        models_reaching_advice(0.01, 0.01, glm::vec3(0.0f), 1.0f, a.model)));
  a.model = BssrdfModel::Tabulated;
  a.albedo = {0.5f, 0.5f, 0.9999f};
  EXPECT_NE(inversion_error(a).find("for the standard model (the tabulated model's inversion curve) at g 0 and eta 1"),
            std::string::npos)
      << inversion_error(a);
}

json scene_with_material(const json& material) {
  return {{"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
          {"objects", json::array({json{{"shape", "sphere"}, {"material", material}}})}};
}

std::string scene_error(const json& material) {
  return test::error_message([&] { parse_scene(scene_with_material(material).dump(), "s.json", "."); });
}

TEST(ArtistParameters, SceneMaterialFromAlbedoAndMeanFreePath) {
  const json material = {{"albedo", {0.8, 0.5, 0.2}}, {"mfp_mm", {1.0, 0.5, 0.25}}, {"g", 0.3},
                         {"eta", 1.4},                {"model", "better-dipole"}};
  const Scene scene = parse_scene(scene_with_material(material).dump(), "s.json", ".");
  ArtistParameters a;
  a.albedo = {0.8f, 0.5f, 0.2f};
  a.mfp_mm = {1.0f, 0.5f, 0.25f};
  a.g = glm::vec3(0.3f);
  a.eta = 1.4f;
  a.model = BssrdfModel::BetterDipole;
  const Material expected = invert_artist_parameters(a, "test").material;
  const Material& m = *scene.objects[0].material;
  EXPECT_EQ(m.sigma_a, expected.sigma_a);
  EXPECT_EQ(m.sigma_s, expected.sigma_s);
  EXPECT_EQ(m.g, glm::vec3(0.3f));
  EXPECT_EQ(m.eta, 1.4f);
  EXPECT_EQ(m.model, BssrdfModel::BetterDipole);
  // One number stands for all three bands.
  const Scene grey = parse_scene(scene_with_material({{"albedo", 0.5}, {"mfp_mm", 2}}).dump(), "s.json", ".");
  EXPECT_NEAR(model_total_reflectance(*grey.objects[0].material, 0.0).total.y, 0.5, kRoundTripTolerance);
}

TEST(ArtistParameters, SceneMaterialErrors) {
  EXPECT_EQ(scene_error({{"albedo", 0.5}, {"mfp_mm", 1}, {"sigma_a", {0.1, 0.1, 0.1}}}),
            "s.json: /objects/0/material/sigma_a: not allowed with albedo and mfp_mm (give either albedo and mfp_mm "
            "or coefficients)");
  EXPECT_EQ(scene_error({{"albedo", 0.5}, {"mfp_mm", 1}, {"preset", "Marble"}}),
            "s.json: /objects/0/material/preset: not allowed with albedo and mfp_mm (give either albedo and mfp_mm "
            "or coefficients)");
  EXPECT_EQ(scene_error({{"albedo", 0.5}}),
            "s.json: /objects/0/material/mfp_mm: missing; albedo needs the mean free path too, e.g. [1, 0.5, 0.25]");
  EXPECT_EQ(scene_error({{"mfp_mm", 1}}),
            "s.json: /objects/0/material/albedo: missing; mfp_mm needs the surface albedo too, e.g. [0.8, 0.6, 0.5]");
  EXPECT_EQ(scene_error({{"albedo", {0.5, 1.5, 0.5}}, {"mfp_mm", 1}}),
            "s.json: /objects/0/material: albedo[1] = 1.5 is out of range; allowed range (0, 1)");
  EXPECT_EQ(scene_error({{"albedo", 0.5}, {"mfp_mm", {1, 0, 1}}}),
            "s.json: /objects/0/material: mfp_mm[1] = 0 is out of range; allowed range (0, inf) mm");
}

// `lucent materials invert --json` prints a material a scene file takes as it is; its flat total is the albedo.
TEST(ArtistParameters, CliPrintsASceneMaterial) {
  const test::CliResult r = test::run_cli(
      "materials invert --albedo 0.8,0.5,0.2 --mfp 1,0.5,0.25 --g 0.3 --eta 1.4 --model standard --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json out = json::parse(r.output);
  const Scene scene = parse_scene(scene_with_material(out["material"]).dump(), "s.json", ".");
  const glm::dvec3 total = model_total_reflectance(*scene.objects[0].material, 0.0).total;
  const double albedo[3] = {0.8, 0.5, 0.2};
  for (int b = 0; b < 3; ++b) {
    EXPECT_NEAR(total[b], albedo[b], kRoundTripTolerance) << "band " << b;
    EXPECT_NEAR(out["flat_total"][b].get<double>(), albedo[b], kRoundTripTolerance) << "band " << b;
  }
  const test::CliResult bad = test::run_cli("materials invert --albedo 0,0.5,0.5 --mfp 1");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(bad.output, "lucent: materials invert: albedo[0] = 0 is out of range; allowed range (0, 1)\n");
  const test::CliResult text = test::run_cli("materials invert --albedo 0.5 --mfp 1");
  EXPECT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("flat total"), std::string::npos) << text.output;
}

}  // namespace
}  // namespace lucent
