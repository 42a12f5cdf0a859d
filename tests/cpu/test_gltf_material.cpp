// test_gltf_material.cpp: glTF 2.0 materials to lucent materials and back (scene/gltf_material.h,
// docs/materials.md): the mapping's values against the formulas worked by hand, objects that take their glTF
// mesh's material ("material": "from_mesh"), the export -> import round trip (exact through extras.lucent, and
// within the inversion's tolerance through the standard extensions alone), and one line for each bad file.
#include <cmath>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../test_support.h"
#include "lucent/error.h"
#include "lucent/scene.h"
#include "lucent/scene_writer.h"
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
  mesh.indices = {0, 1, 2};
  test::TempFile file(".scratch.gltf");
  write_gltf(file.path(), mesh, material);
  std::ifstream in(file.path());
  return json::parse(in);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The material of the test assets: base colour, volume, ior, diffuse transmission and a lucent extra.
const json kArtistMaterial = json::parse(R"({
  "name": "wax",
  "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.3, 1.0]},
  "extensions": {
    "KHR_materials_volume": {"thicknessFactor": 0.02, "attenuationDistance": 0.004, "attenuationColor": [0.9, 0.5, 0.2]},
    "KHR_materials_ior": {"ior": 1.4},
    "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.25, "diffuseTransmissionColorFactor": [1.0, 0.9, 0.8]}
  },
  "extras": {"lucent": {"g": 0.5, "model": "standard"}}
})");

TEST(GltfMaterial, ImportMapping) {
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

  // mfp = d / -ln(c), d = 0.004 m = 4 mm: 37.9649, 5.77078, 2.48534 mm.
  const json lucent = lucent_material_json(m, file.path());
  const double mfp[3] = {37.96488, 5.770780, 2.485340};
  const double albedo[3] = {0.8, 0.5, 0.3};
  for (int b = 0; b < 3; ++b) {
    EXPECT_NEAR(lucent["mfp_mm"][b].get<double>(), mfp[b], 1e-5 * mfp[b]) << b;
    EXPECT_NEAR(lucent["albedo"][b].get<double>(), albedo[b], 1e-7) << b;
  }
  EXPECT_FLOAT_EQ(lucent["eta"].get<float>(), 1.4f);
  EXPECT_EQ(lucent["g"], 0.5);
  EXPECT_EQ(lucent["model"], "standard");

  // Without attenuationColor the distance is the mean free path in every band (the spec's "average distance
  // that light travels in the medium before interacting").
  GltfMaterial grey = m;
  grey.has_attenuation_color = false;
  EXPECT_EQ(lucent_material_json(grey, file.path())["mfp_mm"], json::array({4.0, 4.0, 4.0}));
  // No volume, no diffuse transmission, no lucent extra: opaque.
  GltfMaterial opaque;
  opaque.base_color = {0.2f, 0.3f, 0.4f};
  EXPECT_TRUE(lucent_material_json(opaque, file.path()).is_null());
}

// An object that takes its glTF mesh's material: the inversion of the mapped values; the glTF name.
TEST(GltfMaterial, ObjectTakesTheMeshMaterial) {
  test::TempFile mesh(".gltf");
  write_text(mesh.path(), triangle_gltf(kArtistMaterial).dump());
  const json scene = {{"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
                      {"objects", json::array({json{{"mesh", mesh.path()}, {"material", "from_mesh"}}})}};
  const Scene s = parse_scene(scene.dump(), "s.json", ".");
  const Material& m = *s.objects[0].material;
  EXPECT_EQ(m.name, "wax");
  EXPECT_EQ(m.model, BssrdfModel::StandardDipole);
  EXPECT_EQ(m.g, glm::vec3(0.5f));
  EXPECT_FLOAT_EQ(m.eta, 1.4f);
  const glm::dvec3 total = model_total_reflectance(m, 0.0).total;
  const double albedo[3] = {0.8, 0.5, 0.3}, mfp[3] = {37.96488, 5.770780, 2.485340};
  for (int b = 0; b < 3; ++b) {
    EXPECT_NEAR(total[b], albedo[b], 1e-3) << b;
    EXPECT_NEAR(1.0 / m.sigma_t()[b], mfp[b], 1e-5 * mfp[b]) << b;
  }
  // An opaque glTF material: the object is opaque with the base colour.
  json opaque = triangle_gltf({{"pbrMetallicRoughness", {{"baseColorFactor", {0.25, 0.5, 0.75, 1.0}}}}});
  write_text(mesh.path(), opaque.dump());
  const Scene o = parse_scene(scene.dump(), "s.json", ".");
  EXPECT_FALSE(o.objects[0].material.has_value());
  EXPECT_EQ(o.objects[0].albedo, glm::vec3(0.25f, 0.5f, 0.75f));
}

Material artist_material(float g) {
  const json scene = {{"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
                      {"objects", json::array({json{{"shape", "box"},
                                                    {"material", {{"albedo", {0.7, 0.4, 0.2}},
                                                                  {"mfp_mm", {3.0, 1.0, 0.5}},
                                                                  {"g", g}, {"eta", 1.35}, {"model", "better-dipole"}}}}})}};
  return *parse_scene(scene.dump(), "s.json", ".").objects[0].material;
}

// save_scene writes each object's material into its .gltf; an object reading that file with "from_mesh" gets the
// same coefficients, exactly (extras.lucent), and through the standard extensions alone (extras removed) the same
// sigma_t and flat total (g 0: glTF has no phase function).
TEST(GltfMaterial, ExportImportRoundTrip) {
  for (float g : {0.6f, 0.0f}) {
    const Material original = artist_material(g);
    Scene scene = parse_scene(R"({"lights": [{"direction": [0, -1, 0]}], "objects": [{"shape": "box"}]})", "s.json", ".");
    scene.objects[0].material = original;
    scene.objects[0].name = "box";
    test::TempFile saved(".json");
    save_scene(scene, saved.path());
    const std::string mesh = std::filesystem::path(saved.path()).replace_extension(".meshes").string() + "/0_box.gltf";
    const json scene_doc = {{"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
                            {"objects", json::array({json{{"mesh", mesh}, {"material", "from_mesh"}}})}};
    const Material exact = *parse_scene(scene_doc.dump(), "s.json", ".").objects[0].material;
    EXPECT_EQ(exact.sigma_a, original.sigma_a);
    EXPECT_EQ(exact.sigma_s, original.sigma_s);
    EXPECT_EQ(exact.g, original.g);
    EXPECT_EQ(exact.eta, original.eta);
    EXPECT_EQ(exact.model, original.model);
    if (g != 0.0f) continue;
    json gltf = read_gltf_json(mesh);
    gltf["materials"][0].erase("extras");
    write_text(mesh, gltf.dump());
    const Material standard = *parse_scene(scene_doc.dump(), "s.json", ".").objects[0].material;
    EXPECT_EQ(standard.model, kDefaultBssrdfModel);  // the scene default: glTF does not name a model
    EXPECT_EQ(standard.eta, original.eta);
    const double albedo[3] = {0.7, 0.4, 0.2};
    for (int b = 0; b < 3; ++b) {
      EXPECT_NEAR(standard.sigma_t()[b], original.sigma_t()[b], 1e-5 * original.sigma_t()[b]) << b;
      EXPECT_NEAR(gltf["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"][b].get<double>(), albedo[b], 1e-3);
    }
    std::filesystem::remove_all(std::filesystem::path(mesh).parent_path());
  }
}

// The one-line message a scene with one object {"mesh": <path>, "material": "from_mesh"} gets.
std::string from_mesh_error(const std::string& path) {
  const json scene = {{"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
                      {"objects", json::array({json{{"mesh", path}, {"material", "from_mesh"}}})}};
  return test::error_message([&] { parse_scene(scene.dump(), "s.json", "."); });
}

std::string with_material(const std::string& path, const json& material) {
  write_text(path, triangle_gltf(material).dump());
  return from_mesh_error(path);
}

TEST(GltfMaterial, BadFilesGiveOneLine) {
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
            prefix + ": /materials/0/extensions/KHR_materials_volume/attenuationD...: missing; a translucent "
                     "material needs a mean free path (or extras.lucent.mfp_mm)");
  // attenuationDistance: any positive distance, 0 and negative ones refused under the same stated range.
  for (const double d : {0.0, -1.0}) {
    volume = kArtistMaterial;
    volume["extensions"]["KHR_materials_volume"]["attenuationDistance"] = d;
    EXPECT_EQ(with_material(p, volume),
              prefix + fmt::format(": /materials/0/extensions/KHR_materials_volume/attenuationD...: {:g} is out of "
                                   "range; allowed range (0, inf) m",
                                   d));
  }
  // Too long for a float: its mean free path 1e28 m x 1000 mm/m / -ln(0.9) = 9.49122e31 mm is refused.
  volume = kArtistMaterial;
  volume["extensions"]["KHR_materials_volume"]["attenuationDistance"] = 1e28;
  EXPECT_EQ(with_material(p, volume),
            prefix + ": /materials/0/mfp_mm/0: 9.49122e+31 is out of range; allowed range [-1e+30, 1e+30] mm");
  json ior = kArtistMaterial;
  ior["extensions"]["KHR_materials_ior"]["ior"] = 5;
  EXPECT_EQ(with_material(p, ior),
            prefix + ": /materials/0/extensions/KHR_materials_ior/ior: 5 is out of range; allowed range [1, 3]");
  json black = kArtistMaterial;
  black["pbrMetallicRoughness"]["baseColorFactor"] = {0.0, 0.5, 0.5, 1.0};
  EXPECT_EQ(with_material(p, black),
            prefix + ": /materials/0/pbrMetallicRoughness/baseColorFactor/0: 0 is out of range for a translucent "
                     "material's surface albedo; allowed range (0, 1)");
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

  test::TempFile glb(".glb");
  write_text(glb.path(), std::string("glTF\x01\0\0\0", 8) + std::string(20, '\0'));
  EXPECT_EQ(test::error_message([&] { read_gltf_json(glb.path()); }),
            glb.path() + ": binary glTF version 1; lucent reads version 2");
  write_text(glb.path(), std::string("glTF\x02\0\0\0\0\0\0\0\xe8\x03\0\0JSON{}", 22));
  EXPECT_EQ(test::error_message([&] { read_gltf_json(glb.path()); }),
            glb.path() + ": binary glTF: JSON chunk of 1000 bytes runs past the end of the file");
  write_text(glb.path(), "{}");
  EXPECT_EQ(test::error_message([&] { read_gltf_json(glb.path()); }),
            glb.path() + ": not a binary glTF (no 'glTF' header)");
  const json shape = {{"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
                      {"objects", json::array({json{{"shape", "sphere"}, {"material", "from_mesh"}}})}};
  EXPECT_EQ(test::error_message([&] { parse_scene(shape.dump(), "s.json", "."); }),
            "s.json: /objects/0/material: \"from_mesh\" needs a glTF mesh (.gltf or .glb)");
}

// A .glb: the JSON chunk is read (padded to 4 bytes, as the container requires).
TEST(GltfMaterial, BinaryGltf) {
  std::string text = triangle_gltf(kArtistMaterial).dump();
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
