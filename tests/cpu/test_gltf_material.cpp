// test_gltf_material.cpp: glTF 2.0 materials to lucent materials and back (scene/gltf_material.h,
// docs/materials.md): the mapping's values against the formulas worked by hand, objects that take their glTF
// mesh's material ("material": "from_mesh"), the export -> import round trip (exact through extras.lucent, and
// within the inversion's tolerance through the standard extensions alone), the one warning line of ignored fields,
// and one error line at a key of the file for each bad one.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../test_support.h"
#include "lucent/error.h"
#include "lucent/scene.h"
#include "lucent/scene_writer.h"
#include "lucent/warning.h"
#include "lucent/image.h"
#include "bssrdf/multipole.h"
#include "materials/artist_parameters.h"
#include "materials/model_total_reflectance.h"
#include "scene/gltf_material.h"

namespace lucent {
namespace {

using nlohmann::json;

// A glTF document of one triangle (its buffer embedded) whose primitive uses material 0, `material`.
json triangle_gltf(const json& material) {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  mesh.uvs = {{0, 0}, {1, 0}, {0, 1}};
  mesh.indices = {0, 1, 2};
  test::TempFile file(".scratch.gltf");
  write_gltf(file.path(), mesh, material);
  std::ifstream in(file.path());
  return json::parse(in);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

json read_json(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

// The material of the test assets: base colour, volume, ior, diffuse transmission and a lucent extra.
const json kArtistMaterial = json::parse(R"({
  "name": "wax",
  "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.3, 1.0], "metallicFactor": 0},
  "extensions": {
    "KHR_materials_volume": {"thicknessFactor": 0.02, "attenuationDistance": 0.004, "attenuationColor": [0.9, 0.5, 0.2]},
    "KHR_materials_ior": {"ior": 1.4},
    "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.25, "diffuseTransmissionColorFactor": [1.0, 0.9, 0.8]}
  },
  "extras": {"lucent": {"g": 0.5, "model": "standard"}}
})");

const json kLight = json::array({json{{"direction", {0.0, -1.0, 0.0}}}});

// The scene's first object, its mesh `path` taking the glTF material; `warnings` receives the warnings.
SceneObject from_mesh(const std::string& path, std::vector<std::string>* warnings = nullptr, float scale_mm = 1.0f) {
  const json scene = {{"lights", kLight}, {"scale_mm", scale_mm},
                      {"objects", json::array({json{{"mesh", path}, {"material", "from_mesh"}}})}};
  std::vector<std::string> seen;
  const ScopedWarningHandler handler([&](const std::string& m) { seen.push_back(m); });
  SceneObject object = parse_scene(scene.dump(), "s.json", ".").objects[0];
  if (warnings) *warnings = seen;
  return object;
}

TEST(GltfMaterial, ImportReadsTheFile) {
  test::TempFile file(".gltf");
  write_text(file.path(), triangle_gltf(kArtistMaterial).dump());
  const GltfMaterial m = read_gltf_material(file.path());
  EXPECT_EQ(m.index, 0);
  EXPECT_EQ(m.name, "wax");
  EXPECT_EQ(m.base_color, glm::vec3(0.8f, 0.5f, 0.3f));
  EXPECT_TRUE(m.has_volume);
  EXPECT_FLOAT_EQ(m.thickness_factor, 0.02f);
  EXPECT_DOUBLE_EQ(m.attenuation_distance_m, 0.004);
  EXPECT_EQ(m.attenuation_color, glm::vec3(0.9f, 0.5f, 0.2f));
  EXPECT_FLOAT_EQ(m.ior, 1.4f);
  EXPECT_TRUE(m.has_diffuse_transmission);
  EXPECT_FLOAT_EQ(m.diffuse_transmission_factor, 0.25f);
  EXPECT_EQ(m.diffuse_transmission_color, glm::vec3(1.0f, 0.9f, 0.8f));
  EXPECT_TRUE(m.ignored.empty());
}

// KHR_materials_volume is absorption (sigma_a = -ln(c) / d, the spec's sigma_t with sigma_s = 0); the surface
// albedo is what glTF's lobes give: A = (1 - f) B + f D c^(t / d) with t / d = 0.02 / 0.004 = 5:
// A = 0.75 (0.8, 0.5, 0.3) + 0.25 (1, 0.9, 0.8) (0.59049, 0.03125, 0.00032) = (0.7476225, 0.38203125, 0.225064).
TEST(GltfMaterial, VolumeIsAbsorptionAndTheLobesGiveTheSurfaceAlbedo) {
  test::TempFile file(".gltf");
  write_text(file.path(), triangle_gltf(kArtistMaterial).dump());
  const Material m = *from_mesh(file.path()).material;
  EXPECT_EQ(m.name, "wax");
  EXPECT_EQ(m.model, BssrdfModel::StandardDipole);
  EXPECT_EQ(m.g, glm::vec3(0.5f));
  EXPECT_FLOAT_EQ(m.eta, 1.4f);
  const double albedo[3] = {0.7476225, 0.38203125, 0.225064};
  const double sigma_a[3] = {0.0263401289, 0.1732867951, 0.4023594781};  // -ln(c) / 4 mm
  const glm::dvec3 total = model_total_reflectance(m, 0.0).total;
  for (int b = 0; b < 3; ++b) {
    EXPECT_NEAR(total[b], albedo[b], 1e-3) << b;
    EXPECT_NEAR(m.sigma_a[b], sigma_a[b], 2e-3 * sigma_a[b]) << b;
  }
}

// A glass-style volume whose only colour is the attenuation colour (0.9, 0.6, 0.3 at 2 cm, transmission 1, no base
// colour: glTF's default white): the object's colour follows c, T = c^(t / d) = c at t = d. Reading c as
// extinction with a white albedo (mean free paths 190, 39, 17 mm) made red the band that leaks out of the object.
TEST(GltfMaterial, HueFollowsTheAttenuationColourWhenItIsTheOnlyColour) {
  const json glass = json::parse(R"({"extensions": {
    "KHR_materials_transmission": {"transmissionFactor": 1},
    "KHR_materials_volume": {"thicknessFactor": 0.02, "attenuationDistance": 0.02, "attenuationColor": [0.9, 0.6, 0.3]}}})");
  test::TempFile file(".gltf");
  write_text(file.path(), triangle_gltf(glass).dump());
  std::vector<std::string> warnings;
  const Material m = *from_mesh(file.path(), &warnings, 1000.0f).material;
  const glm::dvec3 total = model_total_reflectance(m, 0.0).total;
  const double c[3] = {0.9, 0.6, 0.3};
  for (int b = 0; b < 3; ++b) {
    EXPECT_NEAR(total[b], c[b], 1e-3) << b;
    EXPECT_NEAR(m.sigma_a[b], -std::log(c[b]) / 20.0, 2e-3 * -std::log(c[b]) / 20.0) << b;
    EXPECT_LT(1.0f / m.sigma_t()[b], 2.0f) << b;  // mm: no longer 190, 39, 17
  }
  EXPECT_FLOAT_EQ(m.eta, 1.5f);  // glTF's default ior

  // thicknessFactor is in the mesh's space, attenuationDistance in the world's: under a node scaled by 0.5 the
  // thickness is d / 2, T = c^0.5.
  json scaled = triangle_gltf(glass);
  scaled["nodes"][0]["matrix"] = {0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1};
  write_text(file.path(), scaled.dump());
  const glm::dvec3 half = model_total_reflectance(*from_mesh(file.path(), &warnings, 1000.0f).material, 0.0).total;
  for (int b = 0; b < 3; ++b) EXPECT_NEAR(half[b], std::sqrt(c[b]), 1e-3) << b;
}

// KHR_materials_volume_scatter gives the medium whole: sigma_t = -ln(c) / d, alpha from the multi-scatter colour by
// Kulla and Conty's formula (0.5 -> 0.9117089, 0.8 -> 0.9905888, worked by hand), g = scatterAnisotropy.
TEST(GltfMaterial, VolumeScatterGivesTheMediumWhole) {
  EXPECT_NEAR(single_scatter_albedo(0.5), 0.911708855, 1e-8);
  EXPECT_NEAR(single_scatter_albedo(0.8), 0.990588780, 1e-8);
  EXPECT_NEAR(multiscatter_albedo(0.911708855), 0.5, 1e-8);
  json scatter = json::parse(R"({"extensions": {
    "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 1},
    "KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 0.01, "attenuationColor": [0.9, 0.8, 0.7]},
    "KHR_materials_volume_scatter": {"multiscatterColorFactor": [0.8, 0.5, 0.5], "scatterAnisotropy": 0.3}}})");
  test::TempFile file(".gltf");
  write_text(file.path(), triangle_gltf(scatter).dump());
  const Material m = *from_mesh(file.path()).material;
  const double c[3] = {0.9, 0.8, 0.7}, alpha[3] = {0.990588780, 0.911708855, 0.911708855};
  for (int b = 0; b < 3; ++b) {
    const double sigma_t = -std::log(c[b]) / 10.0;
    EXPECT_NEAR(m.sigma_t()[b], sigma_t, 1e-6 * sigma_t) << b;
    EXPECT_NEAR(m.sigma_s[b] / m.sigma_t()[b], alpha[b], 1e-6) << b;
  }
  EXPECT_EQ(m.g, glm::vec3(0.3f));
}

// Opaque glTF materials make the object opaque with the base colour; a missing baseColorFactor is glTF's white.
TEST(GltfMaterial, OpaqueMaterialsGiveTheBaseColour) {
  test::TempFile file(".gltf");
  write_text(file.path(), triangle_gltf({{"pbrMetallicRoughness", {{"baseColorFactor", {0.25, 0.5, 0.75, 1.0}}}}}).dump());
  const SceneObject o = from_mesh(file.path());
  EXPECT_FALSE(o.material.has_value());
  EXPECT_EQ(o.albedo, glm::vec3(0.25f, 0.5f, 0.75f));
  write_text(file.path(), triangle_gltf({{"name", "plain"}}).dump());
  EXPECT_EQ(from_mesh(file.path()).albedo, glm::vec3(1.0f));
}

// Every field lucent does not use is named, in one line per material.
TEST(GltfMaterial, IgnoredFieldsAreNamedInOneLine) {
  json m = kArtistMaterial;
  m["pbrMetallicRoughness"]["roughnessFactor"] = 0.4;
  m["pbrMetallicRoughness"]["metallicFactor"] = 0.5;
  m["emissiveFactor"] = {0.1, 0.0, 0.0};
  m["alphaMode"] = "BLEND";
  m["extensions"]["KHR_materials_specular"] = {{"specularFactor", 0.5}};
  test::TempFile file(".gltf");
  json doc = triangle_gltf(m);
  doc["materials"][0]["doubleSided"] = true;
  write_text(file.path(), doc.dump());
  std::vector<std::string> warnings;
  from_mesh(file.path(), &warnings);
  std::erase_if(warnings, [&](const std::string& w) { return w.rfind(file.path(), 0) != 0; });  // the scene's own
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], file.path() + ": /materials/0 ('wax'): lucent does not use metallicFactor 0.5, roughnessFactor "
                                       "0.4 (the boundary is smooth; the methods' specular roughness is a method "
                                       "parameter), emissiveFactor, alphaMode BLEND, doubleSided (objects are closed "
                                       "volumes), KHR_materials_specular");
}

std::string base64_text(const std::string& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t n = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size()) n |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= static_cast<unsigned char>(bytes[i + 2]);
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

// A textured material with diffuse transmission and no baseColorFactor (glTF's white) loads: its albedo map is
// A = (1 - f) B + f D T per texel, f = 0.5, D = 1, T = c^(t / d) = 0.5 (c = 0.5, t = d), B the texel (sRGB 8-bit
// values 128, 200, 64, 255 decoded: 0.2158605, 0.5775804, 0.0512695, 1).
TEST(GltfMaterial, TexturedDiffuseTransmissionWithoutBaseColorFactor) {
  ImageRGBA8 image;
  image.width = 2, image.height = 2;
  image.pixels = {128, 128, 128, 255, 200, 200, 200, 255, 64, 64, 64, 255, 255, 255, 255, 255};
  json material = json::parse(R"({"extensions": {
    "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.5},
    "KHR_materials_volume": {"thicknessFactor": 0.01, "attenuationDistance": 0.01, "attenuationColor": [0.5, 0.5, 0.5]}},
    "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})");
  json doc = triangle_gltf(material);
  doc["textures"] = json::array({{{"source", 0}}});
  doc["images"] = json::array({{{"uri", "data:image/png;base64," + base64_text(encode_png(image))}}});
  test::TempFile file(".gltf");
  write_text(file.path(), doc.dump());
  const Material m = *from_mesh(file.path()).material;
  ASSERT_TRUE(m.textured());
  const double texel[4] = {0.0512695, 1.0, 0.2158605, 0.5775804};  // rows from the bottom: the file's last row first
  for (int i = 0; i < 4; ++i) {
    const double albedo = 0.5 * texel[i] + 0.25;
    const double total = flat_total_of_albedo(m.model, m.maps->alpha[static_cast<std::size_t>(i)].x, m.g.x, m.eta);
    EXPECT_NEAR(total, std::min(albedo, 0.998), 1e-3) << i;
  }
}

// A thin-walled material (KHR_materials_diffuse_transmission, no volume) is a multipole sheet: glTF's diffuse
// reflectance (1 - f) B and transmittance f D are the sheet's totals (the model's own, multipole_beam_totals, at the
// material's reduced albedo and optical thickness, within 0.01), and the surface, here one triangle, is thickened
// into a closed solid: the triangle, its copy 0.5 mm behind (the default, with a warning) and three walls.
TEST(GltfMaterial, ThinWalledDiffuseTransmissionIsAMultipoleSheet) {
  const json material = json::parse(R"({"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.5, 0.4, 1]},
    "extensions": {"KHR_materials_ior": {"ior": 1.4},
      "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.3, "diffuseTransmissionColorFactor": [0.8, 0.6, 0.4]}}})");
  test::TempFile file(".gltf");
  write_text(file.path(), triangle_gltf(material).dump());
  std::vector<std::string> warnings;
  const SceneObject o = from_mesh(file.path(), &warnings, 10.0f);  // the triangle's legs are 10 mm
  ASSERT_TRUE(o.material);
  const Material& m = *o.material;
  EXPECT_EQ(m.model, BssrdfModel::Multipole);
  EXPECT_FLOAT_EQ(m.thickness_mm, 0.5f);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("rendered as a sheet 0.5 mm thick; extras.lucent.thickness_mm sets it"), std::string::npos)
      << warnings[0];
  const glm::vec3 R{0.42f, 0.35f, 0.28f}, T{0.24f, 0.18f, 0.12f};  // (1 - 0.3) B and 0.3 D
  for (int b = 0; b < 3; ++b) {
    const float sigma_s_prime = m.sigma_s_prime()[b], sigma_t_prime = sigma_s_prime + m.sigma_a[b];
    const shader::vec2 totals = shader::multipole_beam_totals(sigma_s_prime / sigma_t_prime, 1.4f, sigma_t_prime * 0.5f);
    EXPECT_NEAR(totals.x, R[b], 0.01) << b;
    EXPECT_NEAR(totals.y, T[b], 0.01) << b;
  }
  // The solid: 1 + 1 + 3 x 2 triangles; every edge met by two triangles in opposite directions (closed, consistently
  // wound); the back face 0.05 scene units (0.5 mm at 10 mm per unit) behind the front along -z.
  ASSERT_EQ(o.mesh.indices.size(), 3u * 8u);
  std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> edges;
  for (std::size_t t = 0; t < o.mesh.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 a = o.mesh.positions[o.mesh.indices[t + static_cast<std::size_t>(k)]];
      const glm::vec3 b = o.mesh.positions[o.mesh.indices[t + static_cast<std::size_t>((k + 1) % 3)]];
      ++edges[{{a.x, a.y, a.z}, {b.x, b.y, b.z}}];
    }
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ((edges.count({edge.second, edge.first})), 1u) << "an edge without its opposite: the solid is open";
  }
  float z_min = 0.0f;
  for (const glm::vec3& p : o.mesh.positions) z_min = std::min(z_min, p.z);
  EXPECT_NEAR(z_min, -0.05f, 1e-6f);

  // Given in extras.lucent.thickness_mm: no warning, that thickness.
  json given = material;
  given["extras"] = {{"lucent", {{"thickness_mm", 2.0}}}};
  write_text(file.path(), triangle_gltf(given).dump());
  const SceneObject thick = from_mesh(file.path(), &warnings, 10.0f);
  EXPECT_TRUE(warnings.empty()) << warnings[0];
  EXPECT_FLOAT_EQ(thick.material->thickness_mm, 2.0f);
}

Material artist_material(float g) {
  const json scene = {{"lights", kLight},
                      {"objects", json::array({json{{"shape", "box"},
                                                    {"material", {{"albedo", {0.7, 0.4, 0.2}},
                                                                  {"mfp_mm", {3.0, 1.0, 0.5}},
                                                                  {"g", g}, {"eta", 1.35}, {"model", "better-dipole"}}}}})}};
  return *parse_scene(scene.dump(), "s.json", ".").objects[0].material;
}

// save_scene writes each object's material into its .gltf; an object reading that file with "from_mesh" gets the
// same coefficients, exactly (extras.lucent), and through the standard extensions alone (extras removed) the same
// sigma_t and single-scattering albedo (KHR_materials_volume_scatter), g the bands' mean.
TEST(GltfMaterial, ExportImportRoundTrip) {
  for (float g : {0.6f, 0.0f}) {
    const Material original = artist_material(g);
    Scene scene = parse_scene(R"({"lights": [{"direction": [0, -1, 0]}], "objects": [{"shape": "box"}]})", "s.json", ".");
    scene.objects[0].material = original;
    scene.objects[0].name = "box";
    test::TempFile saved(".json");
    save_scene(scene, saved.path());
    const std::string mesh = std::filesystem::path(saved.path()).replace_extension(".meshes").string() + "/0_box.gltf";
    const Material exact = *from_mesh(mesh).material;
    EXPECT_EQ(exact.sigma_a, original.sigma_a);
    EXPECT_EQ(exact.sigma_s, original.sigma_s);
    EXPECT_EQ(exact.g, original.g);
    EXPECT_EQ(exact.eta, original.eta);
    EXPECT_EQ(exact.model, original.model);
    json gltf = read_json(mesh);
    gltf["materials"][0].erase("extras");
    write_text(mesh, gltf.dump());
    const Material standard = *from_mesh(mesh).material;
    EXPECT_EQ(standard.model, kDefaultBssrdfModel);  // the scene default: glTF does not name a model
    EXPECT_EQ(standard.eta, original.eta);
    EXPECT_EQ(standard.g, glm::vec3(g));
    for (int b = 0; b < 3; ++b) {
      EXPECT_NEAR(standard.sigma_t()[b], original.sigma_t()[b], 1e-5 * original.sigma_t()[b]) << b;
      const double alpha = original.sigma_s[b] / original.sigma_t()[b];
      EXPECT_NEAR(standard.sigma_s[b] / standard.sigma_t()[b], alpha, 1e-5 * (1.0 - alpha)) << b;
    }
    std::filesystem::remove_all(std::filesystem::path(mesh).parent_path());
  }
}

// The one-line message a scene with one object {"mesh": <path>, "material": "from_mesh"} gets.
std::string from_mesh_error(const std::string& path) {
  return test::error_message([&] { from_mesh(path); });
}

std::string with_material(const std::string& path, const json& material) {
  write_text(path, triangle_gltf(material).dump());
  return from_mesh_error(path);
}

TEST(GltfMaterial, BadFilesGiveOneLineAtAKeyOfTheFile) {
  test::TempFile file(".gltf");
  const std::string p = file.path(), prefix = "s.json: /objects/0/material: " + p;
  json volume = kArtistMaterial;
  volume["extensions"]["KHR_materials_volume"]["attenuationColor"] = {0.5, 1.0, 0.5};
  EXPECT_EQ(with_material(p, volume),
            prefix + ": /materials/0/extensions/KHR_materials_volume/attenuationC...: 1 is out of range; allowed "
                     "range (0, 1) (1 is no extinction: no mean free path)");  // pointers are cut at 60 characters
  volume = kArtistMaterial;
  volume["extensions"]["KHR_materials_volume"].erase("attenuationDistance");
  EXPECT_EQ(with_material(p, volume),
            prefix + ": /materials/0/extensions/KHR_materials_volume: no attenuationDistance (glTF's default: "
                     "infinite, a clear medium); lucent's medium needs one, or extras.lucent.mfp_mm");
  json thin = kArtistMaterial;  // thin-walled specular transmission: no sheet for it (diffuse: see below)
  thin["extensions"].erase("KHR_materials_volume");
  thin["extensions"].erase("KHR_materials_diffuse_transmission");
  thin["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", 0.5}};
  EXPECT_EQ(with_material(p, thin),
            prefix + ": /materials/0/extensions/KHR_materials_transmission: thin-walled (no "
                     "KHR_materials_volume): lucent renders a medium and needs its attenuationDistance, or "
                     "extras.lucent.mfp_mm");
  thin = kArtistMaterial;
  thin["extensions"].erase("KHR_materials_volume");
  thin["extras"]["lucent"]["thickness_mm"] = -1;
  EXPECT_EQ(with_material(p, thin),
            prefix + ": /materials/0/extras/lucent/thickness_mm: -1: the sheet's thickness in mm, a number in (0, 1e6]");
  // attenuationDistance: any positive distance, 0 and negative ones refused under the same stated range.
  for (const double d : {0.0, -1.0}) {
    volume = kArtistMaterial;
    volume["extensions"]["KHR_materials_volume"]["attenuationDistance"] = d;
    EXPECT_EQ(with_material(p, volume),
              prefix + fmt::format(": /materials/0/extensions/KHR_materials_volume/attenuationD...: {:g} is out of "
                                   "range; allowed range (0, inf) m",
                                   d));
  }
  // Too long for a float: 1e35 m of attenuation is a mean free path beyond 1e30 mm.
  volume = kArtistMaterial;
  volume["extensions"]["KHR_materials_volume"]["attenuationDistance"] = 1e35;
  EXPECT_EQ(with_material(p, volume),
            prefix + ": /materials/0/extensions/KHR_materials_volume/attenuationD...: 1e+35 m gives the mean free "
                     "path 4.46133e+35 mm in band 0; lucent's range is (1e-30, 1e30) mm");
  json anisotropy = kArtistMaterial;
  anisotropy["extensions"]["KHR_materials_volume_scatter"] = {{"multiscatterColorFactor", {0.5, 0.5, 0.5}},
                                                              {"scatterAnisotropy", 1}};
  EXPECT_EQ(with_material(p, anisotropy),
            prefix + ": /materials/0/extensions/KHR_materials_volume_scatter/scat...: 1 is out of range; lucent's "
                     "phase functions take (-1, 1)");
  json ior = kArtistMaterial;
  ior["extensions"]["KHR_materials_ior"]["ior"] = 5;
  EXPECT_EQ(with_material(p, ior),
            prefix + ": /materials/0/extensions/KHR_materials_ior/ior: 5 is out of range; allowed range [1, 3]");
  json black = kArtistMaterial;
  black["pbrMetallicRoughness"]["baseColorFactor"] = {0.0, 0.5, 0.5, 1.0};
  black["extensions"].erase("KHR_materials_diffuse_transmission");
  black["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", 0.5}};
  EXPECT_EQ(with_material(p, black),
            prefix + ": /materials/0/pbrMetallicRoughness/baseColorFactor/0: makes the surface albedo 0; lucent's "
                     "media reflect light");
  json over = kArtistMaterial;
  over["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 1.5, 0.5, 1.0};
  EXPECT_EQ(with_material(p, over), prefix + ": /materials/0/pbrMetallicRoughness/baseColorFactor/1: 1.5 is not a "
                                             "number in [0, 1]");
  json no_scatter = kArtistMaterial;
  no_scatter["extensions"]["KHR_materials_volume_scatter"] = json::object();
  EXPECT_EQ(with_material(p, no_scatter),
            prefix + ": /materials/0/extensions/KHR_materials_volume_scatter: multi-scatter albedo 0 gives the "
                     "single-scatter albedo 5.71678e-06; lucent's media scatter and absorb (allowed range (0, 1) "
                     "exclusive) (absent: glTF's default [0, 0, 0] scatters nothing)");
  json two = triangle_gltf(kArtistMaterial);
  two["meshes"][0]["primitives"].push_back(two["meshes"][0]["primitives"][0]);
  two["meshes"][0]["primitives"][1]["material"] = 1;
  two["materials"].push_back(kArtistMaterial);
  write_text(p, two.dump());
  EXPECT_EQ(from_mesh_error(p), prefix + ": /meshes: the primitives use 2 materials (0, 1); an object takes one");
  json bad_extra = kArtistMaterial;
  bad_extra["extras"]["lucent"]["sigma_a"] = {0.1, 0.1, 0.1};
  EXPECT_EQ(with_material(p, bad_extra),
            prefix + ": /materials/0: give exactly one of sigma_s and sigma_s_prime");
  json missing_image = triangle_gltf(kArtistMaterial);
  missing_image["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  missing_image["textures"] = json::array({{{"source", 0}}});
  missing_image["images"] = json::array({{{"uri", "no_such_image.png"}}});
  write_text(p, missing_image.dump());
  EXPECT_EQ(from_mesh_error(p), prefix + ": /images/0/uri: cannot load 'no_such_image.png'");
  missing_image["images"][0]["uri"] = "data:image/png;base64,aGVsbG8=";  // "hello"
  write_text(p, missing_image.dump());
  EXPECT_EQ(from_mesh_error(p), prefix + ": /images/0: cannot read PNG: not a PNG or JPEG image");
}

TEST(GltfMaterial, MalformedContainersGiveOneLine) {
  test::TempFile glb(".glb");
  const std::string prefix = glb.path() + ": cannot read glTF: ";  // the mesh loader refuses them first in a scene
  for (const std::string& bytes :
       {std::string("glTF\x01\0\0\0", 8) + std::string(20, '\0'), std::string("glTF\x02\0\0\0\0\0\0\0\xe8\x03\0\0JSON{}", 22),
        std::string("{}"), std::string("glTF", 4), std::string(1000, '[')}) {
    write_text(glb.path(), bytes);
    const std::string message = test::error_message([&] { read_gltf_material(glb.path()); });
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
  }
  const json shape = {{"lights", kLight}, {"objects", json::array({json{{"shape", "sphere"}, {"material", "from_mesh"}}})}};
  EXPECT_EQ(test::error_message([&] { parse_scene(shape.dump(), "s.json", "."); }),
            "s.json: /objects/0/material: \"from_mesh\" needs a glTF mesh (.gltf or .glb)");
}

// ---- texture coordinates: textureInfo.texCoord and KHR_texture_transform ----

// A textured translucent triangle: vertices (0,0,0), (1,0,0), (0,1,0) with TEXCOORD_0 (s, t) = (0, 1), (1, 1),
// (0, 0) (write_gltf's, lucent's (0, 0), (1, 0), (0, 1) with t = 1 - v) and TEXCOORD_1 (0.25, 0.5), (0.75, 0.5),
// (0.25, 1); `texture_info` is the material's baseColorTexture.
json two_set_gltf(const json& texture_info) {
  json material = kArtistMaterial;
  material["pbrMetallicRoughness"]["baseColorTexture"] = texture_info;
  json doc = triangle_gltf(material);
  ImageRGBA8 image;
  image.width = 2, image.height = 1;
  image.pixels = {128, 100, 80, 255, 200, 150, 120, 255};
  doc["textures"] = json::array({{{"source", 0}}});
  doc["images"] = json::array({{{"uri", "data:image/png;base64," + base64_text(encode_png(image))}}});
  const float set1[6] = {0.25f, 0.5f, 0.75f, 0.5f, 0.25f, 1.0f};
  const std::string bytes(reinterpret_cast<const char*>(set1), sizeof set1);
  doc["buffers"].push_back({{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64_text(bytes)}});
  doc["bufferViews"].push_back({{"buffer", doc["buffers"].size() - 1}, {"byteOffset", 0}, {"byteLength", bytes.size()}});
  doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1}, {"componentType", 5126}, {"count", 3},
                              {"type", "VEC2"}});
  doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = doc["accessors"].size() - 1;
  return doc;
}

// The object's texture coordinates at the triangle's vertices (0,0,0), (1,0,0), (0,1,0), in that order.
std::vector<glm::vec2> vertex_uvs(const SceneObject& object) {
  std::vector<glm::vec2> uvs;
  for (const glm::vec3 corner : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)})
    for (std::size_t i = 0; i < object.mesh.positions.size(); ++i)
      if (object.mesh.positions[i] == corner) uvs.push_back(object.mesh.uvs.at(i));
  return uvs;
}

void expect_uvs(const std::vector<glm::vec2>& got, const std::vector<glm::vec2>& expected) {
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_NEAR(got[i].x, expected[i].x, 1e-6f) << "vertex " << i;
    EXPECT_NEAR(got[i].y, expected[i].y, 1e-6f) << "vertex " << i;
  }
}

// KHR_texture_transform, offset (0.5, 0.25), rotation pi/2, scale (2, 0.5): T R S (s, t, 1) with R's rows
// (cos, sin), (-sin, cos) gives s' = 0.5 t + 0.5 and t' = -2 s + 0.25, so the vertices' (s, t) = (0, 1), (1, 1),
// (0, 0) become (1, 0.25), (1, -1.75), (0.5, 0.25), lucent's (u, v) = (s', 1 - t') = (1, 0.75), (1, 2.75),
// (0.5, 0.75). The file requires the extension, which is now read.
TEST(GltfMaterial, TextureTransformGivesTheHandComputedCoordinates) {
  json doc = two_set_gltf(json::parse(R"({"index": 0, "extensions": {"KHR_texture_transform":
      {"offset": [0.5, 0.25], "rotation": 1.5707963267948966, "scale": [2, 0.5]}}})"));
  doc["extensionsUsed"] = doc["extensionsRequired"] = json::array({"KHR_texture_transform"});
  test::TempFile file(".gltf");
  write_text(file.path(), doc.dump());
  std::vector<std::string> warnings;
  const SceneObject object = from_mesh(file.path(), &warnings);
  ASSERT_TRUE(object.material && object.material->textured());
  expect_uvs(vertex_uvs(object), {{1.0f, 0.75f}, {1.0f, 2.75f}, {0.5f, 0.75f}});
  for (const std::string& w : warnings) EXPECT_EQ(w.find("KHR_texture_transform"), std::string::npos) << w;
  // Without the transform the coordinates are the file's TEXCOORD_0 (u, 1 - t).
  doc = two_set_gltf({{"index", 0}});
  write_text(file.path(), doc.dump());
  expect_uvs(vertex_uvs(from_mesh(file.path())), {{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}});
}

// texCoord 1 reads TEXCOORD_1: (s, t) = (0.25, 0.5), (0.75, 0.5), (0.25, 1) -> (u, v) = (0.25, 0.5), (0.75, 0.5),
// (0.25, 0); KHR_texture_transform's texCoord overrides the textureInfo's, here with offset (0.5, 0): (0.75, 0.5),
// (1.25, 0.5), (0.75, 0).
TEST(GltfMaterial, TexCoordOneSelectsTheSecondSet) {
  test::TempFile file(".gltf");
  write_text(file.path(), two_set_gltf({{"index", 0}, {"texCoord", 1}}).dump());
  expect_uvs(vertex_uvs(from_mesh(file.path())), {{0.25f, 0.5f}, {0.75f, 0.5f}, {0.25f, 0.0f}});
  write_text(file.path(), two_set_gltf(json::parse(R"({"index": 0, "texCoord": 0, "extensions":
      {"KHR_texture_transform": {"texCoord": 1, "offset": [0.5, 0]}}})")).dump());
  expect_uvs(vertex_uvs(from_mesh(file.path())), {{0.75f, 0.5f}, {1.25f, 0.5f}, {0.75f, 0.0f}});
}

// A set the primitives do not have, a set or transform value that is not one: one line at the key.
TEST(GltfMaterial, BadTextureCoordinatesGiveOneLineAtTheKey) {
  test::TempFile file(".gltf");
  const std::string p = file.path(), prefix = "s.json: /objects/0/material: " + p;
  auto error = [&](const json& texture_info) {
    write_text(p, two_set_gltf(texture_info).dump());
    return from_mesh_error(p);
  };
  const std::string at = ": /materials/0/pbrMetallicRoughness/baseColorTexture";
  EXPECT_EQ(error({{"index", 0}, {"texCoord", 2}}),
            prefix + at + "/texCoord: 2: /meshes/0/primitives/0 has no attribute TEXCOORD_2");
  json transform = {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 9}}}}}};
  EXPECT_EQ(error(transform),
            prefix + ": /materials/0/pbrMetallicRoughness/baseColorTexture/extens...: 9: lucent reads "
                     "texture coordinate sets 0 to 7");
  transform["extensions"]["KHR_texture_transform"] = {{"texCoord", -1}};
  EXPECT_EQ(error(transform),
            prefix + ": /materials/0/pbrMetallicRoughness/baseColorTexture/extens...: expected a "
                     "texture coordinate set (a whole number >= 0), got -1");
  transform["extensions"]["KHR_texture_transform"] = {{"offset", {0.5, "a"}}};
  EXPECT_EQ(error(transform),
            prefix + ": /materials/0/pbrMetallicRoughness/baseColorTexture/extens...: \"a\" is not a "
                     "finite number");
  transform["extensions"]["KHR_texture_transform"] = {{"scale", {2.0}}};
  EXPECT_EQ(error(transform),
            prefix + ": /materials/0/pbrMetallicRoughness/baseColorTexture/extens...: expected 2 "
                     "numbers, got [2.0]");
  transform["extensions"]["KHR_texture_transform"] = {{"rotation", "half"}};
  EXPECT_EQ(error(transform),
            prefix + ": /materials/0/pbrMetallicRoughness/baseColorTexture/extens...: expected a "
                     "number, got \"half\"");
  // Finite values whose coordinates leave the float range.
  transform["extensions"]["KHR_texture_transform"] = {{"scale", {1e300, 1.0}}};
  EXPECT_EQ(error(transform),
            prefix + ": /materials/0/pbrMetallicRoughness/baseColorTexture/extens...: turns vertex "
                     "1's texture coordinates (1, 1) into (1e+300, 1), beyond a float");
  // A number beyond a double (JSON has no NaN or infinity): one line naming the file.
  write_text(p, std::string(two_set_gltf({{"index", 0}}).dump()).replace(
                    two_set_gltf({{"index", 0}}).dump().find("\"index\":0"), 9,
                    R"("index":0,"extensions":{"KHR_texture_transform":{"rotation":1e999}})"));
  const std::string overflow = from_mesh_error(p);
  EXPECT_EQ(overflow.find('\n'), std::string::npos) << overflow;
  EXPECT_NE(overflow.find(p), std::string::npos) << overflow;
}

// A .glb: the JSON chunk (padded to 4 bytes, as the container requires) and the binary chunk.
TEST(GltfMaterial, BinaryGltf) {
  json doc = triangle_gltf(kArtistMaterial);
  std::string text = doc.dump();
  text.resize((text.size() + 3) / 4 * 4, ' ');
  auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  test::TempFile glb(".glb");
  write_text(glb.path(), "glTF" + u32(2) + u32(static_cast<std::uint32_t>(20 + text.size())) +
                             u32(static_cast<std::uint32_t>(text.size())) + "JSON" + text);
  const GltfMaterial m = read_gltf_material(glb.path());
  EXPECT_EQ(m.name, "wax");
  EXPECT_DOUBLE_EQ(m.attenuation_distance_m, 0.004);
}

}  // namespace
}  // namespace lucent
