// test_scene_writer.cpp: scene_to_json / save_scene write what load_scene reads back into an equal scene:
// every field the loader reads, for each light type, procedural and file meshes, deformations, blobs, an
// environment map, custom and preset materials and every method's parameters.
#include <filesystem>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "denoise/denoise_params.h"
#include "lucent/scene_writer.h"
#include "../test_support.h"
#include "../test_paths.h"

namespace lucent {
namespace {

namespace fs = std::filesystem;

fs::path test_dir() {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path dir = fs::path(::testing::TempDir()) / (std::string("lucent_") + test->test_suite_name() + "_" + test->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void expect_near(glm::vec3 a, glm::vec3 b, float tolerance, const std::string& what) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << what << "[" << i << "]";
}

// The same triangles in the same order: positions exact, normals within a renormalisation's rounding
// (assimp may merge identical vertices, so indices may differ).
void expect_same_triangles(const TriangleMesh& a, const TriangleMesh& b, const std::string& what) {
  ASSERT_EQ(a.indices.size(), b.indices.size()) << what;
  int position_mismatches = 0, normal_mismatches = 0;
  for (std::size_t i = 0; i < a.indices.size(); ++i) {
    position_mismatches += a.positions[a.indices[i]] != b.positions[b.indices[i]];
    normal_mismatches += glm::length(a.normals[a.indices[i]] - b.normals[b.indices[i]]) > 1e-6f;
  }
  EXPECT_EQ(position_mismatches, 0) << what;
  EXPECT_EQ(normal_mismatches, 0) << what;
}

void expect_equal_scenes(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.scale_mm, b.scale_mm);
  for (const ParamDecl& decl : lucent::denoise::kDenoiseParams) {  // written when enabled; otherwise off
    const std::string key(decl.name);
    if (lucent::denoise::denoise_settings(a.denoise).enabled) {
      EXPECT_EQ(to_string(a.denoise.all().at(key)), to_string(b.denoise.all().at(key))) << "denoise." << key;
    }
  }
  EXPECT_EQ(lucent::denoise::denoise_settings(a.denoise).enabled, lucent::denoise::denoise_settings(b.denoise).enabled);
  EXPECT_EQ(a.camera.eye, b.camera.eye);
  EXPECT_EQ(a.camera.target, b.camera.target);
  expect_near(a.camera.up, b.camera.up, 1e-6f, "camera.up");
  EXPECT_EQ(a.camera.fov_y_deg, b.camera.fov_y_deg);
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (std::size_t i = 0; i < a.lights.size(); ++i) {
    expect_near(a.lights[i].direction, b.lights[i].direction, 1e-6f, "direction");
    EXPECT_EQ(a.lights[i].radiance, b.lights[i].radiance);
    EXPECT_EQ(a.lights[i].specular, b.lights[i].specular);
  }
  ASSERT_EQ(a.point_lights.size(), b.point_lights.size());
  for (std::size_t i = 0; i < a.point_lights.size(); ++i) {
    const PointLight &p = a.point_lights[i], &q = b.point_lights[i];
    EXPECT_EQ(p.position, q.position);
    EXPECT_EQ(p.intensity, q.intensity);
    EXPECT_EQ(p.spot, q.spot);
    expect_near(p.direction, q.direction, 1e-6f, "spot direction");
    EXPECT_EQ(p.inner_deg, q.inner_deg);
    EXPECT_EQ(p.outer_deg, q.outer_deg);
  }
  ASSERT_EQ(a.environment.has_value(), b.environment.has_value());
  if (a.environment) {
    EXPECT_TRUE(fs::equivalent(a.environment->file, b.environment->file));
    EXPECT_EQ(a.environment->light_count, b.environment->light_count);
    EXPECT_EQ(a.environment->intensity, b.environment->intensity);
    EXPECT_EQ(a.environment->background, b.environment->background);
  }
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const SceneObject &o = a.objects[i], &p = b.objects[i];
    EXPECT_EQ(o.name, p.name);
    EXPECT_EQ(o.deformation.type, p.deformation.type);
    EXPECT_EQ(o.deformation.amplitude, p.deformation.amplitude);
    EXPECT_EQ(o.deformation.period_s, p.deformation.period_s);
    EXPECT_EQ(o.blob_resolution, p.blob_resolution);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(o.world_from_object[c][r], p.world_from_object[c][r], 1e-6f) << o.name;
    expect_same_triangles(o.mesh, p.mesh, o.name);
    ASSERT_EQ(o.material.has_value(), p.material.has_value()) << o.name;
    if (o.material) {
      EXPECT_EQ(o.material->name, p.material->name);
      EXPECT_EQ(o.material->sigma_a, p.material->sigma_a);
      EXPECT_EQ(o.material->sigma_s, p.material->sigma_s);
      EXPECT_EQ(o.material->g, p.material->g);
      EXPECT_EQ(o.material->eta, p.material->eta);
      EXPECT_EQ(o.material->model, p.material->model);
      EXPECT_EQ(o.material->field.type, p.material->field.type);
      EXPECT_EQ(o.material->field.scale_mm, p.material->field.scale_mm);
      EXPECT_EQ(o.material->field.contrast, p.material->field.contrast);
      EXPECT_EQ(o.material->field.volume != nullptr, p.material->field.volume != nullptr);
      if (o.material->field.volume) {
        EXPECT_EQ(o.material->field.volume->values, p.material->field.volume->values);
      }
    } else {
      EXPECT_EQ(o.albedo, p.albedo);
    }
  }
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.method_params.all(), b.method_params.all());
  EXPECT_EQ(a.render.width, b.render.width);
  EXPECT_EQ(a.render.height, b.render.height);
  EXPECT_EQ(a.render.frames, b.render.frames);
  EXPECT_EQ(a.render.seed, b.render.seed);
  EXPECT_EQ(a.render.exposure, b.render.exposure);
  EXPECT_EQ(a.render.tonemap, b.render.tonemap);
  EXPECT_EQ(a.render.background, b.render.background);
  EXPECT_EQ(a.render.fps, b.render.fps);
}

Scene round_trip(const Scene& scene) {
  fs::path path = test_dir() / "saved.json";
  save_scene(scene, path.string());
  return load_scene(path.string());
}

class SceneWriterRoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(SceneWriterRoundTrip, LoadSaveLoadGivesAnEqualScene) {
  Scene original = load_scene(std::string(LUCENT_SCENES_DIR) + "/" + GetParam());
  Scene again = round_trip(original);
  expect_equal_scenes(original, again);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SceneWriterRoundTrip,
                         ::testing::Values("default.json", "candle.json", "candle_melting.json", "blobs.json",
                                           "bunny_spot.json", "bunny_environment.json", "lamp_shade.json",
                                           "bunny_marble_veins.json", "deforming_inclusion.json"),
                         [](const auto& test_param) { return fs::path(test_param.param).stem().string(); });

// Edited values of every kind (as the viewer changes them) survive: custom coefficients, models, tone mapping,
// method parameters of the other methods, render settings, a changed scale.
TEST(SceneWriter, EditedValuesRoundTrip) {
  Scene scene = default_scene();
  scene.scale_mm = 3.25f;
  scene.camera.eye = {0.1f, 2.7f, 4.9f};
  scene.camera.fov_y_deg = 27.5f;
  Material& m = *scene.objects[0].material;
  m.name = "custom";
  m.sigma_a = {0.0123f, 0.045f, 0.1f};
  m.sigma_s = {1.1f, 1.3f, 1.7f};
  m.g = {0.1f, 0.2f, 0.3f};
  m.eta = 1.41f;
  m.model = BssrdfModel::PhotonBeamDiffusion;
  scene.objects[1].material->model = BssrdfModel::StandardDipole;
  scene.lights[0].direction = glm::normalize(glm::vec3(-0.3f, -0.9f, 0.2f));
  scene.render.tonemap = ToneMapOperator::Reinhard;
  scene.render.exposure = -0.75f;
  scene.render.seed = 4000000000u;
  Scene denoised = default_scene({"denoise={\"enabled\": true, \"iterations\": 2, \"sigma_luminance\": 3.5}"});
  scene.denoise = denoised.denoise;
  for (const char* method : {"per-pixel", "voxel-paths", "radiosity-maps"}) {
    Scene s = default_scene({std::string("method={\"name\": \"") + method + "\"}"});
    scene.method = s.method;
    scene.method_params = s.method_params;
    expect_equal_scenes(scene, round_trip(scene));
  }
}

TEST(SceneWriter, PresetMaterialsAreWrittenByName) {
  nlohmann::json j = scene_to_json(default_scene());
  EXPECT_EQ(j["objects"][0]["material"]["preset"], "Potato");
  EXPECT_EQ(j["objects"][1]["material"]["preset"], "Marble");
  EXPECT_EQ(j["objects"][2]["albedo"].size(), 3u);
  EXPECT_FALSE(j["objects"][2].contains("material"));
}

// Rotations of the loader's convention (x, then y, then z) and uniform scales decompose back to a matrix equal
// within float rounding; shapes the format cannot express are refused with the object's name.
TEST(SceneWriter, TransformsDecomposeIntoTranslateRotateScale) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> angle(-180.0f, 180.0f), unit(-5.0f, 5.0f), scale(0.1f, 10.0f);
  for (int i = 0; i < 200; ++i) {
    ObjectTransform t{{unit(rng), unit(rng), unit(rng)}, {angle(rng), angle(rng) * 0.5f, angle(rng)}, scale(rng)};
    glm::vec3 r = glm::radians(t.rotate_deg);
    glm::mat4 m = glm::translate(glm::mat4(1.0f), t.translate);
    m = glm::rotate(m, r.z, glm::vec3(0, 0, 1));
    m = glm::rotate(m, r.y, glm::vec3(0, 1, 0));
    m = glm::rotate(m, r.x, glm::vec3(1, 0, 0));
    m = glm::scale(m, glm::vec3(t.scale));
    ObjectTransform d = decompose_object_transform(m, "object");
    glm::vec3 rd = glm::radians(d.rotate_deg);
    glm::mat4 back = glm::translate(glm::mat4(1.0f), d.translate);
    back = glm::rotate(back, rd.z, glm::vec3(0, 0, 1));
    back = glm::rotate(back, rd.y, glm::vec3(0, 1, 0));
    back = glm::rotate(back, rd.x, glm::vec3(1, 0, 0));
    back = glm::scale(back, glm::vec3(d.scale));
    for (int c = 0; c < 4; ++c)
      for (int row = 0; row < 4; ++row) ASSERT_NEAR(back[c][row], m[c][row], 1e-5f * (1.0f + t.scale)) << i;
  }
  glm::mat4 stretched = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 2.0f, 1.0f));
  EXPECT_NE(test::error_message([&] { decompose_object_transform(stretched, "object 'vase'"); }).find("object 'vase'"),
            std::string::npos);
}

TEST(SceneWriter, UnwritableFileNamesThePath) {
  std::string message = test::error_message([] { save_scene(default_scene(), "/proc/lucent_no/such.json"); });
  EXPECT_NE(message.find("/proc/lucent_no"), std::string::npos) << message;
}

}  // namespace
}  // namespace lucent
