// test_materials.cpp: the compiled-in material presets against shared/data/materials.json, preset lookup,
// BSSRDF model names, sigma_tr, and the exact messages of validate_material.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "lucent/error.h"
#include "lucent/material.h"

namespace lucent {
namespace {

void expect_vec3_eq(const glm::vec3& actual, const glm::vec3& expected) {
  for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(actual[i], expected[i]) << "component " << i;
}

// The lucent::Error message validate_material throws, or "" when it accepts the material.
std::string validation_error(const Material& material) {
  try {
    validate_material(material, "scene.json: material");
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

Material marble() { return material_from_preset(*find_material_preset("Marble")); }

TEST(MaterialPresets, HasAll47MeasuredMaterials) {
  EXPECT_EQ(material_presets().size(), 47u);
}

TEST(MaterialPresets, LookupIgnoresCaseSpacesAndPunctuation) {
  const MaterialPreset* juice = find_material_preset("white_grapefruit_juice");
  ASSERT_NE(juice, nullptr);
  EXPECT_STREQ(juice->name, "White Grapefruit Juice");
  const MaterialPreset* marble_preset = find_material_preset("MARBLE");
  ASSERT_NE(marble_preset, nullptr);
  EXPECT_STREQ(marble_preset->name, "Marble");
  const MaterialPreset* shampoo = find_material_preset("head&shoulders-shampoo");
  ASSERT_NE(shampoo, nullptr);
  EXPECT_STREQ(shampoo->name, "Head & Shoulders Shampoo");
  EXPECT_EQ(find_material_preset("unobtainium"), nullptr);
  EXPECT_EQ(find_material_preset(""), nullptr);
}

TEST(MaterialPresets, MarbleMatchesJensenTable) {
  const MaterialPreset& preset = *find_material_preset("Marble");
  expect_vec3_eq(preset.sigma_s, glm::vec3(2.19f, 2.62f, 3.0f));  // sigma_s' (reduced)
  expect_vec3_eq(preset.sigma_a, glm::vec3(0.0021f, 0.0041f, 0.0071f));
  expect_vec3_eq(preset.g, glm::vec3(0.0f));
  EXPECT_FLOAT_EQ(preset.eta, 1.5f);
  EXPECT_TRUE(preset.reduced);
  expect_vec3_eq(marble().sigma_s_prime(), glm::vec3(2.19f, 2.62f, 3.0f));
}

TEST(MaterialPresets, NarasimhanEntriesAreUnreducedWithPerBandG) {
  const MaterialPreset& preset = *find_material_preset("Strawberry Shampoo");
  EXPECT_FALSE(preset.reduced);
  expect_vec3_eq(preset.g, glm::vec3(0.927f, 0.935f, 0.994f));
  expect_vec3_eq(preset.sigma_s, glm::vec3(0.00215f, 0.00245f, 0.00253f));
  expect_vec3_eq(preset.sigma_a, glm::vec3(0.01449f, 0.05796f, 0.07582f));
  EXPECT_FLOAT_EQ(preset.eta, 1.33f);
}

TEST(MaterialPresets, ChickenKeepsPbrtRedAbsorptionWithANote) {
  const MaterialPreset& preset = *find_material_preset("Chicken1");
  EXPECT_FLOAT_EQ(preset.sigma_a[0], 0.015f);
  EXPECT_NE(std::string(preset.note).find("0.0015"), std::string::npos);
  EXPECT_STREQ(find_material_preset("Apple")->note, "");
}

TEST(MaterialPresets, EveryPresetHasANameSourceAndNote) {
  for (const MaterialPreset& preset : material_presets()) {
    ASSERT_NE(preset.name, nullptr);
    EXPECT_NE(preset.source, nullptr) << preset.name;
    EXPECT_NE(preset.note, nullptr) << preset.name;
    EXPECT_EQ(find_material_preset(preset.name), &preset) << preset.name;
  }
}

TEST(Material, FromPresetCopiesCoefficientsAndName) {
  const Material material = marble();
  EXPECT_EQ(material.name, "Marble");
  EXPECT_FLOAT_EQ(material.eta, 1.5f);
  expect_vec3_eq(material.sigma_a, glm::vec3(0.0021f, 0.0041f, 0.0071f));
}

TEST(Material, SigmaTrOfPotatoMatchesHandValues) {
  const Material potato = material_from_preset(*find_material_preset("Potato"));
  const double sigma_a[3] = {0.0024, 0.009, 0.12};
  const double sigma_s_prime[3] = {0.68, 0.7, 0.55};
  const glm::vec3 sigma_tr = potato.sigma_tr();
  for (int i = 0; i < 3; ++i) {
    const double expected = std::sqrt(3.0 * sigma_a[i] * (sigma_a[i] + sigma_s_prime[i]));
    EXPECT_NEAR(sigma_tr[i], expected, 1e-6 * expected) << "band " << i;
  }
}

TEST(Material, BssrdfModelNamesRoundTrip) {
  EXPECT_EQ(to_string(BssrdfModel::StandardDipole), "standard");
  EXPECT_EQ(to_string(BssrdfModel::DirectionalDipole), "directional");
  EXPECT_EQ(parse_bssrdf_model("standard"), BssrdfModel::StandardDipole);
  EXPECT_EQ(parse_bssrdf_model("directional"), BssrdfModel::DirectionalDipole);
  EXPECT_EQ(parse_bssrdf_model("photon"), std::nullopt);
}

TEST(ValidateMaterial, AcceptsAMeasuredPreset) {
  EXPECT_EQ(validation_error(marble()), "");
  EXPECT_EQ(validation_error(material_from_preset(*find_material_preset("Strawberry Shampoo"))), "");
}

TEST(ValidateMaterial, RejectsNegativeCoefficient) {
  Material material = marble();
  material.sigma_a[1] = -0.1f;
  EXPECT_EQ(validation_error(material),
            "scene.json: material: sigma_a[1] = -0.1 is negative; allowed range [0, inf) mm^-1");
}

TEST(ValidateMaterial, RejectsNaNAndInfinity) {
  Material material = marble();
  material.sigma_s[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(validation_error(material), "scene.json: material: sigma_s[0] is NaN; allowed range [0, inf) mm^-1");
  material = marble();
  material.sigma_s[2] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(validation_error(material),
            "scene.json: material: sigma_s[2] = inf is infinite; allowed range [0, inf) mm^-1");
}

TEST(ValidateMaterial, RejectsGOutOfRange) {
  Material material = marble();
  material.g[2] = 1.2f;
  EXPECT_EQ(validation_error(material), "scene.json: material: g[2] = 1.2 is out of range; allowed range (-1, 1)");
  material.g[2] = -1.0f;
  EXPECT_EQ(validation_error(material), "scene.json: material: g[2] = -1 is out of range; allowed range (-1, 1)");
}

TEST(ValidateMaterial, RejectsEtaOutOfRange) {
  Material material = marble();
  material.eta = 0.5f;
  EXPECT_EQ(validation_error(material), "scene.json: material: eta = 0.5 is out of range; allowed range [1, 3]");
  material.eta = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(validation_error(material), "scene.json: material: eta is NaN; allowed range [1, 3]");
}

TEST(ValidateMaterial, RejectsZeroAbsorptionOrReducedScattering) {
  Material material = marble();
  material.sigma_a[0] = 0.0f;
  EXPECT_EQ(validation_error(material),
            "scene.json: material: sigma_a[0] = 0 must be positive for the diffusion models; "
            "allowed range (0, inf) mm^-1");
  // Spectralon has sigma_a = 0 in the table: a valid measurement the diffusion models cannot use.
  EXPECT_NE(validation_error(material_from_preset(*find_material_preset("Spectralon"))), "");
  // Merlot scatters only in red.
  EXPECT_EQ(validation_error(material_from_preset(*find_material_preset("Merlot"))),
            "scene.json: material: sigma_s'[1] = sigma_s[1] * (1 - g[1]) = 0 must be positive for the diffusion "
            "models; allowed range (0, inf) mm^-1");
}

}  // namespace
}  // namespace lucent
