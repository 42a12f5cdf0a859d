// test_gltf_scene_export.cpp: the whole-scene glTF export (save_scene_gltf, lucent/scene_writer.h) read back through
// tinygltf: names, transforms, materials (the exact coefficients in extras.lucent; sigma_t, alpha and eta through
// the standard extensions), the camera and the lights with the documented unit conversions, in .gltf and .glb.
#include <cmath>
#include <filesystem>
#include <string>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli_runner.h"
#include "../test_paths.h"
#include "../test_support.h"
#include "lucent/image.h"
#include "lucent/scene.h"
#include "lucent/scene_writer.h"
#include "materials/material_maps.h"
#include "scene/gltf_material.h"
#include "scene/gltf_reader.h"

namespace lucent {
namespace {

using nlohmann::json;

glm::mat4 node_matrix(const tinygltf::Node& node) {
  glm::mat4 m(1.0f);
  if (node.matrix.size() == 16)
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(node.matrix[static_cast<std::size_t>(i)]);
  return m;
}

const tinygltf::Node& named_node(const tinygltf::Model& model, const std::string& name) {
  for (const tinygltf::Node& node : model.nodes)
    if (node.name == name) return node;
  throw std::runtime_error("no node " + name);
}


Scene export_scene() {
  Scene scene = default_scene({"scale_mm=10", "method.roughness=0.09"});
  scene.point_lights.push_back({{0.5f, 2.0f, 1.0f}, {0.002f, 0.001f, 0.0005f}});
  PointLight spot{{0.0f, 3.0f, 0.0f}, {0.004f, 0.004f, 0.004f}, true, {0.0f, -1.0f, 0.0f}, 20.0f, 35.0f};
  scene.point_lights.push_back(spot);
  return scene;
}

void check_round_trip(const Scene& scene, const std::string& path) {
  save_scene_gltf(scene, path);
  const GltfFile file = read_gltf_file(path);
  const tinygltf::Model& model = file.model;
  const float metres = scene.scale_mm / 1000.0f;

  // Objects: a node and a mesh named after each, under the node that scales scene units to metres.
  const tinygltf::Node& root = model.nodes[static_cast<std::size_t>(model.scenes[0].nodes[0])];
  ASSERT_EQ(root.scale.size(), 3u);
  EXPECT_FLOAT_EQ(static_cast<float>(root.scale[0]), metres);
  ASSERT_EQ(root.children.size(), scene.objects.size());
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(root.children[i])];
    EXPECT_EQ(node.name, object.name);
    const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(node.mesh)];
    EXPECT_EQ(mesh.name, object.name);
    EXPECT_EQ(node_matrix(node), object.world_from_object) << object.name;
    const tinygltf::Material& material = model.materials[static_cast<std::size_t>(mesh.primitives[0].material)];
    EXPECT_NEAR(material.pbrMetallicRoughness.roughnessFactor, 0.3, 1e-6);  // sqrt of the method's GGX alpha 0.09
    if (!object.material) continue;
    const Material& m = *object.material;
    const JsonLocation at{path, "/materials"};
    const json extras = gltf_json(material.extras_json_string, at)["lucent"];
    EXPECT_EQ(extras["sigma_a"], json::array({m.sigma_a.x, m.sigma_a.y, m.sigma_a.z}));
    EXPECT_EQ(extras["sigma_s"], json::array({m.sigma_s.x, m.sigma_s.y, m.sigma_s.z}));
    EXPECT_EQ(extras["eta"].get<float>(), m.eta);
    EXPECT_EQ(extras["model"], std::string(to_string(m.model)));
    const json ext = gltf_json(material.extensions_json_string, at);
    EXPECT_GT(ext["KHR_materials_transmission"]["transmissionFactor"].get<double>(), 0.0);  // translucent in Blender
    EXPECT_FLOAT_EQ(ext["KHR_materials_ior"]["ior"].get<float>(), m.eta);
    const json& volume = ext["KHR_materials_volume"];
    const double d_mm = volume["attenuationDistance"].get<double>() * 1000.0;
    for (int b = 0; b < 3; ++b) {
      const auto band = static_cast<std::size_t>(b);
      const double sigma_t = -std::log(volume["attenuationColor"][band].get<double>()) / d_mm;
      EXPECT_NEAR(sigma_t, m.sigma_t()[b], 1e-5 * m.sigma_t()[b]) << object.name << " " << b;
      const double alpha = single_scatter_albedo(ext["KHR_materials_volume_scatter"]["multiscatterColorFactor"][band].get<double>());
      EXPECT_NEAR(alpha, m.sigma_s[b] / m.sigma_t()[b], 1e-6) << object.name << " " << b;
    }
  }

  // The camera: a perspective camera at the eye (metres), looking at the target, the scene's vertical field of view.
  const tinygltf::Node& camera_node = named_node(model, "camera");
  const tinygltf::Camera& camera = model.cameras[static_cast<std::size_t>(camera_node.camera)];
  EXPECT_EQ(camera.type, "perspective");
  EXPECT_NEAR(camera.perspective.yfov, glm::radians(static_cast<double>(scene.camera.fov_y_deg)), 1e-6);
  EXPECT_NEAR(camera.perspective.aspectRatio, static_cast<double>(scene.render.width) / scene.render.height, 1e-9);
  const glm::mat4 camera_frame = node_matrix(camera_node);
  const glm::vec3 eye = glm::vec3(camera_frame[3]) / metres;
  const glm::vec3 forward = -glm::vec3(camera_frame[2]);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(eye[k], scene.camera.eye[k], 1e-4f);
    EXPECT_NEAR(forward[k], glm::normalize(scene.camera.target - scene.camera.eye)[k], 1e-5f);
  }

  // The lights: directional in lux and point/spot in candela, 683 lm/W; the light's -z its direction.
  std::size_t directional = 0, point = 0;
  for (const tinygltf::Node& node : model.nodes) {
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) continue;
    const auto& light = model.lights[static_cast<std::size_t>(ext->second.Get("light").GetNumberAsInt())];
    const glm::mat4 frame = node_matrix(node);
    glm::vec3 colour;
    for (int k = 0; k < 3; ++k) colour[k] = static_cast<float>(light.color[static_cast<std::size_t>(k)] * light.intensity / 683.0);
    if (light.type == "directional") {
      const DirectionalLight& d = scene.lights[directional++];
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(colour[k], d.radiance[k], 1e-6f * d.radiance[k]);
        EXPECT_NEAR(-frame[2][k], d.direction[k], 1e-6f);
      }
    } else {
      const PointLight& p = scene.point_lights[point++];
      EXPECT_EQ(light.type, p.spot ? "spot" : "point");
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(colour[k], p.intensity[k], 1e-6f * p.intensity[k]);
        EXPECT_NEAR(frame[3][k] / metres, p.position[k], 1e-5f);
      }
      if (p.spot) {
        EXPECT_NEAR(light.spot.outerConeAngle, glm::radians(static_cast<double>(p.outer_deg)), 1e-6);
        EXPECT_NEAR(-frame[2][1], -1.0f, 1e-6f);
      }
    }
  }
  EXPECT_EQ(directional, scene.lights.size());
  EXPECT_EQ(point, scene.point_lights.size());
}

TEST(GltfSceneExport, ReadsBackThroughTinygltf) {
  const Scene scene = export_scene();
  test::TempFile gltf(".gltf"), glb(".glb");
  check_round_trip(scene, gltf.path());
  check_round_trip(scene, glb.path());
}

TEST(GltfSceneExport, RefusesToOverwriteItsInputs) {
  const Scene scene = load_scene(std::string(LUCENT_SOURCE_DIR) + "/scenes/default.json");
  EXPECT_NE(test::error_message([&] { save_scene_gltf(scene, "/proc/lucent_no/such.gltf"); }).find("/proc/lucent_no"),
            std::string::npos);
  EXPECT_NE(test::error_message([&] { save_scene_gltf(scene, "out.obj"); }).find(".obj"), std::string::npos);
}

// ---- textures: the albedo map as the base colour texture ----

// A 7 x 5 albedo map, each texel its own 8-bit colour, all inside the surface albedos the model reaches (linear
// 0.021 to 0.51), and a scene of one box taking it.
Scene textured_scene(const std::string& map_path, const std::string& scene_path) {
  ImageRGBA8 image;
  image.width = 7, image.height = 5;
  image.pixels.resize(4 * 35);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = static_cast<std::uint8_t>(40 + 25 * x), p[1] = static_cast<std::uint8_t>(50 + 30 * y);
      p[2] = static_cast<std::uint8_t>(60 + 3 * (x + 7 * y)), p[3] = 255;
    }
  write_png(map_path, image);
  const json scene = {
      {"scale_mm", 1000}, {"lights", json::array({{{"direction", {0, -1, 0}}}})},
      {"objects", json::array({{{"name", "block"}, {"shape", "box"}, {"size", {1.0, 0.5, 0.8}},
                                {"material", {{"albedo_map", std::filesystem::path(map_path).filename().string()},
                                              {"mfp_mm", {1.0, 0.5, 0.25}}, {"g", 0.3}, {"eta", 1.4}}}}})}};
  return parse_scene(scene.dump(), scene_path, std::filesystem::path(map_path).parent_path().string());
}

// Export, then the file read back as an object's mesh and "from_mesh" material: the base colour texture is the
// map, texel for texel (the decoded 8-bit values equal, so the same bytes; and the re-imported material's alpha per
// texel equal, exactly), and each vertex's texture coordinates within 1e-6 (glTF stores 1 - v; 1 - (1 - v) is
// within an ulp of 1).
void check_texture_round_trip(const std::string& exported) {
  const std::filesystem::path folder = std::filesystem::path(testing::TempDir()) / ("lucent_texture_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  const std::string map = (folder / "albedo.png").string();
  const Scene scene = textured_scene(map, (folder / "s.json").string());
  const SceneObject& original = scene.objects[0];
  ASSERT_TRUE(original.material && original.material->textured());
  save_scene_gltf(scene, exported);

  const MapImage source = read_material_map(map, true, "test");
  const GltfMaterial gltf = read_gltf_material(exported);
  ASSERT_TRUE(gltf.base_color_texture.has_value());
  ASSERT_EQ(gltf.base_color_texture->size, source.size);
  for (std::size_t i = 0; i < source.texels.size(); ++i)
    EXPECT_EQ(gltf.base_color_texture->texels[i], source.texels[i]) << "texel " << i;

  const json reimport = {{"scale_mm", 1000}, {"lights", json::array({{{"direction", {0, -1, 0}}}})},
                          {"objects", json::array({{{"mesh", exported}, {"material", "from_mesh"}}})}};
  const Scene again = parse_scene(reimport.dump(), (folder / "t.json").string(), folder.string());
  const SceneObject& object = again.objects[0];
  ASSERT_TRUE(object.material && object.material->textured());
  const MaterialMaps& a = *original.material->maps;
  const MaterialMaps& b = *object.material->maps;
  ASSERT_EQ(b.alpha_size, a.alpha_size);
  for (std::size_t i = 0; i < a.alpha.size(); ++i) EXPECT_EQ(b.alpha[i], a.alpha[i]) << "texel " << i;
  EXPECT_EQ(object.material->g, original.material->g);
  EXPECT_EQ(object.material->eta, original.material->eta);
  EXPECT_EQ(b.base_mfp_mm, a.base_mfp_mm);

  // Vertices: the box's 24 (4 a face), told apart by position and normal (the object's transform is the identity
  // and scale_mm 1000 makes the file's metres the scene's units).
  ASSERT_EQ(object.mesh.positions.size(), original.mesh.positions.size());
  for (std::size_t i = 0; i < original.mesh.positions.size(); ++i) {
    std::size_t found = 0;
    for (std::size_t j = 0; j < object.mesh.positions.size(); ++j) {
      if (glm::length(object.mesh.positions[j] - original.mesh.positions[i]) > 1e-6f ||
          glm::dot(object.mesh.normals[j], original.mesh.normals[i]) < 0.999f)
        continue;
      ++found;
      EXPECT_NEAR(object.mesh.uvs[j].x, original.mesh.uvs[i].x, 1e-6f) << "vertex " << i;
      EXPECT_NEAR(object.mesh.uvs[j].y, original.mesh.uvs[i].y, 1e-6f) << "vertex " << i;
    }
    EXPECT_EQ(found, 1u) << "vertex " << i;
  }
  std::filesystem::remove_all(folder);
}

TEST(GltfSceneExport, AlbedoMapIsTheBaseColourTextureInAGlb) {
  test::TempFile glb(".glb");
  check_texture_round_trip(glb.path());
  const GltfFile file = read_gltf_file(glb.path());
  ASSERT_EQ(file.model.images.size(), 1u);
  EXPECT_EQ(file.model.images[0].mimeType, "image/png");
  EXPECT_GE(file.model.images[0].bufferView, 0);  // in the binary chunk, no file beside it
}

TEST(GltfSceneExport, AlbedoMapIsAPngBesideAGltf) {
  test::TempFile gltf(".gltf");
  const std::string png = std::filesystem::path(gltf.path()).replace_extension("").string() + "_albedo_0.png";
  check_texture_round_trip(gltf.path());
  const GltfFile file = read_gltf_file(gltf.path());
  ASSERT_EQ(file.model.images.size(), 1u);
  EXPECT_EQ(file.model.images[0].uri, std::filesystem::path(png).filename().string());
  EXPECT_TRUE(std::filesystem::is_regular_file(png));
  std::filesystem::remove(png);
}

// The image beside a .gltf is an output like the file: one that would replace the scene's own map is refused,
// and the map is left as it was.
TEST(GltfSceneExport, AnImageThatWouldReplaceAnInputIsRefused) {
  const std::filesystem::path folder = std::filesystem::path(testing::TempDir()) / ("lucent_texture_in_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  const std::string map = (folder / "x_albedo_0.png").string();
  const Scene scene = textured_scene(map, (folder / "s.json").string());
  const std::string before = test::read_text(map);
  const std::string message = test::error_message([&] { save_scene_gltf(scene, (folder / "x.gltf").string()); });
  EXPECT_NE(message.find(map), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_EQ(test::read_text(map), before);
  EXPECT_FALSE(std::filesystem::exists(folder / "x.gltf"));
  std::filesystem::remove_all(folder);
}

// `lucent export`: the scene file as one .glb that tinygltf reads, with the scene's object names; another output
// type is one line and a non-zero exit.
TEST(GltfSceneExport, ExportCommandWritesTheFile) {
  test::TempFile glb(".glb");
  const test::CliResult ok = test::run_cli("export " + std::string(LUCENT_SCENES_DIR) + "/default.json " + glb.path());
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_EQ(ok.output, "wrote " + glb.path() + "\n");
  const GltfFile file = read_gltf_file(glb.path());
  EXPECT_EQ(named_node(file.model, "torus").name, "torus");
  EXPECT_EQ(file.model.lights.size(), 1u);
  const test::CliResult bad = test::run_cli("export " + std::string(LUCENT_SCENES_DIR) + "/default.json out.obj");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(bad.output, "lucent: out.obj: a scene is saved as .gltf or .glb (one glTF file) or .json (a scene file "
                        "and its meshes)\n");
}

}  // namespace
}  // namespace lucent
