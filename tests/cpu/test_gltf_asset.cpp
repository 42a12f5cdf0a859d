// test_gltf_asset.cpp: a glTF made by Blender 3.4's own exporter (tests/data/gltf/translucent_textured.glb, made by
// scripts/make_gltf_translucent_asset.py: a 4 cm ico sphere, a 16 x 16 base colour texture, transmission 1, IOR 1.4,
// a volume of attenuation colour (0.9, 0.6, 0.3) at 2 cm and thickness 4 cm) taken by an object as "from_mesh":
// translucent, its albedo map the texture's texels through A = B c^(t / d) (docs/materials.md), checked per texel
// against the image decoded on its own and the model's forward flat total; the coefficients from the volume.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../test_paths.h"
#include "../test_support.h"
#include "lucent/scene.h"
#include "lucent/scene_writer.h"
#include "lucent/warning.h"
#include "materials/artist_parameters.h"
#include "materials/material_maps.h"
#include "scene/gltf_reader.h"

namespace lucent {
namespace {

std::string blender_asset() { return std::string(LUCENT_TEST_DATA) + "/gltf/translucent_textured.glb"; }

SceneObject blender_object(float scale_mm, std::vector<std::string>& warnings) {
  const nlohmann::json scene = {{"scale_mm", scale_mm},
                                {"lights", nlohmann::json::array({{{"direction", {0.0, -1.0, 0.0}}}})},
                                {"objects", nlohmann::json::array({{{"mesh", blender_asset()}, {"material", "from_mesh"}}})}};
  const ScopedWarningHandler handler([&](const std::string& m) { warnings.push_back(m); });
  return parse_scene(scene.dump(), "s.json", ".").objects[0];
}

// The loader's line for a mean free path comparable to the object, with the object's numbers.
std::string mean_free_path_warning(const SceneObject& object, const char* extent, float scale_mm) {
  const glm::vec3 mfp = 1.0f / object.material->sigma_t();
  return fmt::format("s.json: /objects/0: the mean free path ({:.3g}, {:.3g}, {:.3g}) mm of {}'s material is comparable "
                     "to or larger than the object, {} across at its thinnest (scale_mm {:g}): light crosses it in a "
                     "few scattering steps, which the diffusion models do not see (volpath does)",
                     mfp.x, mfp.y, mfp.z, blender_asset(), extent, scale_mm);
}

TEST(GltfBlenderAsset, TextureIsTheAlbedoMapAndTheVolumeSetsTheCoefficients) {
  std::vector<std::string> warnings;
  const SceneObject object = blender_object(1000.0f, warnings);  // Blender works in metres
  ASSERT_TRUE(object.material.has_value());
  const Material& m = *object.material;
  ASSERT_TRUE(m.textured());
  EXPECT_EQ(m.name, "wax");
  EXPECT_FLOAT_EQ(m.eta, 1.4f);
  EXPECT_EQ(m.maps->alpha_size, glm::ivec2(16, 16));
  ASSERT_EQ(object.mesh.uvs.size(), object.mesh.positions.size());

  // The texture, decoded on its own: the PNG bytes the .glb holds, read as a colour map file.
  const GltfFile file = read_gltf_file(blender_asset());
  ASSERT_EQ(file.model.images.size(), 1u);
  test::TempFile png(".png");
  std::ofstream(png.path(), std::ios::binary)
      .write(reinterpret_cast<const char*>(file.model.images[0].image.data()),
             static_cast<std::streamsize>(file.model.images[0].image.size()));
  const MapImage texture = read_material_map(png.path(), true, "reference");
  ASSERT_EQ(texture.texels.size(), m.maps->alpha.size());

  // A = B T, T = c^(t / d) = c^2 (4 cm / 2 cm), transmission 1; the texel's alpha gives A back as the model's flat total.
  const glm::dvec3 T(0.81, 0.36, 0.09);
  for (std::size_t i = 0; i < texture.texels.size(); i += 7)
    for (int b = 0; b < 3; ++b) {
      const double albedo = texture.texels[i][b] * T[b];
      const double total = flat_total_of_albedo(m.model, m.maps->alpha[i][b], m.g[b], m.eta);
      EXPECT_NEAR(total, albedo, 2e-4 + 1e-3 * albedo) << "texel " << i << " band " << b;
    }
  // KHR_materials_volume is absorption: sigma_a = -ln(c) / 20 mm (the maps' mean texel carries it).
  const double c[3] = {0.9, 0.6, 0.3};
  for (int b = 0; b < 3; ++b) EXPECT_NEAR(m.sigma_a[b], -std::log(c[b]) / 20.0, 3e-3 * -std::log(c[b]) / 20.0) << b;

  // One line names what the file sets and lucent does not use; one gives the mean free paths against the ball.
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0], blender_asset() + ": /materials/0 ('wax'): lucent does not use roughnessFactor 0.2 (the "
                                           "boundary is smooth; the methods' specular roughness is a method parameter), "
                                           "doubleSided (objects are closed volumes)");
  EXPECT_EQ(warnings[1], mean_free_path_warning(object, "38 mm", 1000.0f));
}

// Read at 1 mm a unit (a metre-based file without "scale_mm": 1000), the ball is 0.038 mm across.
TEST(GltfBlenderAsset, MeanFreePathLargerThanTheObjectIsWarnedAbout) {
  std::vector<std::string> warnings;
  const SceneObject object = blender_object(1.0f, warnings);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[1], mean_free_path_warning(object, "0.038 mm", 1.0f));
}

// "save scene as" keeps an object whose albedo map is its glTF's texture as "from_mesh" of that file: the scene
// reads back with the same maps.
TEST(GltfBlenderAsset, SavedSceneTakesTheGltfMaterialAgain) {
  std::vector<std::string> warnings;
  const ScopedWarningHandler handler([&](const std::string& m) { warnings.push_back(m); });
  Scene scene = parse_scene(nlohmann::json{{"scale_mm", 1000},
                                           {"lights", nlohmann::json::array({{{"direction", {0.0, -1.0, 0.0}}}})},
                                           {"objects", nlohmann::json::array({{{"mesh", blender_asset()},
                                                                               {"material", "from_mesh"},
                                                                               {"translate", {0.0, 0.1, 0.0}}}})}}
                                .dump(),
                            "s.json", ".");
  test::TempFile saved(".json");
  save_scene(scene, saved.path());
  const Scene again = load_scene(saved.path());
  ASSERT_TRUE(again.objects[0].material && again.objects[0].material->maps);
  EXPECT_EQ(again.objects[0].material->maps->alpha, scene.objects[0].material->maps->alpha);
  EXPECT_EQ(again.objects[0].material->sigma_a, scene.objects[0].material->sigma_a);
  EXPECT_EQ(again.objects[0].world_from_object, scene.objects[0].world_from_object);
  std::filesystem::remove_all(std::filesystem::path(saved.path()).replace_extension(".meshes"));
}

}  // namespace
}  // namespace lucent
