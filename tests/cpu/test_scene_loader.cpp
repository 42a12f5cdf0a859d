// test_scene_loader.cpp: scene files -> Scene: the built-in default scene, --set overrides, explicit material
// coefficients, mesh objects, the scenes shipped in scenes/, and the exact one-line message of each bad input.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "denoise/denoise_params.h"
#include "lucent/error.h"
#include "../test_support.h"
#include "lucent/environment.h"
#include "lucent/scene.h"
#include "methods/method_info.h"
#include "render/light_views.h"
#include "../test_paths.h"

namespace lucent {
namespace {

using nlohmann::json;

constexpr const char* kSource = "test.json";
constexpr const char* kBaseDir = "/nonexistent/scene/dir";
constexpr const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

void expect_vec3_eq(const glm::vec3& actual, const glm::vec3& expected) {
  for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(actual[i], expected[i]) << "component " << i;
}

// A small valid scene: one translucent sphere, one light. Tests break one thing in it at a time.
json minimal_scene() {
  return json{
      {"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
      {"objects", json::array({json{{"shape", "sphere"}, {"material", "Marble"}}})},
  };
}

Scene parse(const json& doc, const std::vector<std::string>& overrides = {}) {
  return parse_scene(doc.dump(), kSource, kBaseDir, overrides);
}

// The lucent::Error message parse_scene throws for `text`, or "" when it accepts it.
std::string parse_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parse_scene(text, kSource, kBaseDir, overrides);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

std::string parse_error(const json& doc, const std::vector<std::string>& overrides = {}) {
  return parse_error(doc.dump(), overrides);
}

// minimal_scene() with the first object's material replaced.
std::string material_error(const json& material) {
  json doc = minimal_scene();
  doc["objects"][0]["material"] = material;
  return parse_error(doc);
}

// A file under the system temporary folder, removed when the test ends.
class WrittenFile {
 public:
  WrittenFile(const std::string& name, const std::string& text)
      : path_(std::filesystem::temp_directory_path() / ("lucent_test_" + name)) {
    std::ofstream(path_) << text;
  }
  ~WrittenFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  WrittenFile(const WrittenFile&) = delete;
  WrittenFile& operator=(const WrittenFile&) = delete;
  std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

// ---- valid scenes -------------------------------------------------------------------------------

// A point light inside a translucent object and a translucent object without a closed surface render what the
// user does not expect in some renderers (black, or lit in one and dark in the other): one warning each.
TEST(SceneLoader, LightsInsideMediaAndOpenMediaAreWarnedAbout) {
  auto warnings = [](const std::string& text) {
    ::testing::internal::CaptureStderr();
    parse_scene(text, "enclosure", "/");
    return ::testing::internal::GetCapturedStderr();
  };
  const std::string inside = warnings(R"({
    "lights": [{ "type": "point", "position": [0.1, 0.2, 0], "intensity": [1, 1, 1] },
               { "type": "point", "position": [5, 0, 0], "intensity": [1, 1, 1] }],
    "objects": [{ "name": "ball", "shape": "sphere", "material": "Skin1" }] })");
  EXPECT_EQ(inside, "lucent: warning: enclosure: /objects/0 ('ball'): the point light at (0.1, 0.2, 0) is inside this "
                    "translucent object; only the volpath reference renders light from inside a medium (the "
                    "real-time methods and the bssrdf reference light surfaces from outside, where it lights "
                    "nothing)\n");
  const std::string open = warnings(R"({
    "lights": [{ "direction": [0, -1, 0] }],
    "objects": [{ "shape": "plane", "extent": [2, 2], "material": "Skin1" }] })");
  EXPECT_EQ(open.rfind("lucent: warning: enclosure: /objects/0: a translucent object with an open surface (4 edges "
                       "border one triangle only) encloses no medium",
                       0),
            0u)
      << open;
  // A light on a vertex of the sphere (its pole): neither inside nor outside for the estimators.
  const std::string on = warnings(R"({
    "lights": [{ "type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1] }],
    "objects": [{ "name": "ball", "shape": "sphere", "material": "Skin1" }] })");
  EXPECT_EQ(on, "lucent: warning: enclosure: /objects/0 ('ball'): the point light at (0, 1, 0) lies on the surface of "
                "this translucent object (within the ray offsets there): it is neither inside nor outside it for the "
                "estimators, which disagree (volpath lights the medium from one side, the GPU walk not at all); move "
                "it off the surface\n");
  EXPECT_EQ(warnings(R"({ "lights": [{ "type": "point", "position": [5, 0, 0] }],
                          "objects": [{ "shape": "sphere", "material": "Skin1" }, { "shape": "box", "material": "Skin1" },
                                      { "shape": "torus", "material": "Skin1" }] })"),
            "");
}

TEST(SceneLoader, DefaultSceneParses) {
  Scene scene = default_scene();
  EXPECT_EQ(scene.source, "<built-in default scene>");
  ASSERT_EQ(scene.objects.size(), 3u);
  int translucent = 0;
  for (const SceneObject& object : scene.objects) translucent += object.translucent() ? 1 : 0;
  EXPECT_EQ(translucent, 2);
  ASSERT_TRUE(scene.objects[0].translucent());
  EXPECT_EQ(scene.objects[0].name, "torus");
  EXPECT_EQ(scene.objects[0].material->name, "Potato");
  ASSERT_TRUE(scene.objects[1].translucent());
  EXPECT_EQ(scene.objects[1].name, "sphere");
  EXPECT_EQ(scene.objects[1].material->name, "Marble");
  EXPECT_FALSE(scene.objects[2].translucent());
  expect_vec3_eq(scene.objects[2].albedo, glm::vec3(0.55f, 0.55f, 0.58f));
  EXPECT_FLOAT_EQ(scene.scale_mm, 10.0f);
  EXPECT_EQ(scene.method, "radiosity-maps");
  EXPECT_EQ(scene.method_params.integer("K"), 16);
  EXPECT_EQ(scene.method_params.integer("N"), 32);
  EXPECT_EQ(scene.render.width, 640);
  EXPECT_EQ(scene.render.height, 400);
  EXPECT_EQ(scene.render.frames, 8);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_NEAR(glm::length(scene.lights[0].direction), 1.0f, 1e-6f);
  EXPECT_FLOAT_EQ(scene.camera.fov_y_deg, 38.0f);
}

TEST(SceneLoader, DefaultSceneOverrides) {
  Scene scene = default_scene({"method.K=8", "render.width=320", "objects.0.material=\"Skimmilk\""});
  EXPECT_EQ(scene.method_params.integer("K"), 8);
  EXPECT_EQ(scene.method_params.integer("N"), 32);
  EXPECT_EQ(scene.render.width, 320);
  EXPECT_EQ(scene.render.height, 400);
  ASSERT_TRUE(scene.objects[0].translucent());
  EXPECT_EQ(scene.objects[0].material->name, "Skimmilk");
  EXPECT_EQ(scene.objects[1].material->name, "Marble");
}

TEST(SceneLoader, OverrideWithBareStringAndNestedKey) {
  // A value that is not valid JSON is taken as a string; a missing object on the path is created; overrides
  // apply in order.
  Scene scene = parse(minimal_scene(), {"camera.fov_y_deg=50", "render.tonemap=linear",
                                        "objects.0.material={\"preset\": \"Marble\"}",
                                        "objects.0.material.preset=Ketchup"});
  EXPECT_FLOAT_EQ(scene.camera.fov_y_deg, 50.0f);
  EXPECT_EQ(scene.render.tonemap, ToneMapOperator::Linear);
  EXPECT_EQ(scene.objects[0].material->name, "Ketchup");
}

TEST(SceneLoader, DefaultsFilledIn) {
  Scene scene = parse(minimal_scene());
  EXPECT_EQ(scene.source, kSource);
  EXPECT_FLOAT_EQ(scene.scale_mm, 1.0f);
  EXPECT_EQ(scene.method, "radiosity-maps");
  EXPECT_EQ(scene.method_params.integer("K"), 16);
  EXPECT_EQ(scene.method_params.integer("map_size"), 512);
  EXPECT_EQ(scene.render.width, 640);
  EXPECT_EQ(scene.render.height, 480);
  EXPECT_EQ(scene.render.tonemap, ToneMapOperator::Aces);
  EXPECT_EQ(scene.objects[0].name, "/objects/0");
}

TEST(SceneLoader, ExplicitCoefficientsWithScalarG) {
  json doc = minimal_scene();
  doc["objects"][0]["material"] = {
      {"sigma_a", {0.01, 0.02, 0.03}}, {"sigma_s", {1.0, 2.0, 3.0}}, {"g", 0.5}, {"eta", 1.4}};
  Scene scene = parse(doc);
  ASSERT_TRUE(scene.objects[0].translucent());
  const Material& m = *scene.objects[0].material;
  EXPECT_EQ(m.name, "custom");
  expect_vec3_eq(m.sigma_a, glm::vec3(0.01f, 0.02f, 0.03f));
  expect_vec3_eq(m.sigma_s, glm::vec3(1.0f, 2.0f, 3.0f));
  expect_vec3_eq(m.g, glm::vec3(0.5f));
  EXPECT_FLOAT_EQ(m.eta, 1.4f);
  EXPECT_EQ(m.model, kDefaultBssrdfModel);
}

TEST(SceneLoader, ExplicitReducedCoefficientsHaveGZero) {
  json doc = minimal_scene();
  doc["objects"][0]["material"] = {
      {"sigma_a", {0.01, 0.02, 0.03}}, {"sigma_s_prime", {1.0, 2.0, 3.0}}, {"model", "standard"}};
  Scene scene = parse(doc);
  ASSERT_TRUE(scene.objects[0].translucent());
  const Material& m = *scene.objects[0].material;
  expect_vec3_eq(m.sigma_s, glm::vec3(1.0f, 2.0f, 3.0f));
  expect_vec3_eq(m.g, glm::vec3(0.0f));
  expect_vec3_eq(m.sigma_s_prime(), glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_FLOAT_EQ(m.eta, 1.3f);
  EXPECT_EQ(m.model, BssrdfModel::StandardDipole);
}

TEST(SceneLoader, MeshScene) {
  if (!std::filesystem::exists(kBunny)) GTEST_SKIP() << kBunny << " is not installed";
  json doc = minimal_scene();
  doc["objects"][0] = {{"name", "bunny"}, {"mesh", kBunny}, {"material", {{"preset", "Skin1"}}}};
  WrittenFile file("mesh_scene.json", doc.dump(2));
  Scene scene = load_scene(file.path());
  EXPECT_EQ(scene.source, file.path());
  ASSERT_EQ(scene.objects.size(), 1u);
  const SceneObject& bunny = scene.objects[0];
  EXPECT_EQ(bunny.name, "bunny");
  ASSERT_TRUE(bunny.translucent());
  EXPECT_EQ(bunny.material->name, "Skin1");
  EXPECT_GT(bunny.mesh.indices.size() / 3, 1000u);
  EXPECT_EQ(bunny.mesh.indices.size() % 3, 0u);
  EXPECT_EQ(bunny.mesh.normals.size(), bunny.mesh.positions.size());
}

TEST(SceneLoader, ShippedScenesLoad) {
  const std::filesystem::path dir = LUCENT_SCENES_DIR;
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  if (std::filesystem::is_directory(dir, ec)) {
    for (const auto& entry : std::filesystem::directory_iterator(dir))
      if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
  }
  if (files.empty()) GTEST_SKIP() << "no scene files in " << dir;
  std::sort(files.begin(), files.end());
  for (const auto& path : files) {
    SCOPED_TRACE(path.string());
    try {
      Scene scene = load_scene(path.string());
      EXPECT_FALSE(scene.objects.empty());
    } catch (const Error& error) {
      ADD_FAILURE() << error.what();
    }
  }
}

// Every registered method can be tried from a shipped scene (`lucent render scenes/<file>.json`), and the README's
// table of scenes names that file, so a user never has to compose `--set method=...` to see a method.
TEST(SceneLoader, EveryMethodHasAShippedSceneInTheReadme) {
  std::ifstream readme_file(std::filesystem::path(LUCENT_SOURCE_DIR) / "README.md");
  ASSERT_TRUE(readme_file) << "README.md";
  const std::string readme((std::istreambuf_iterator<char>(readme_file)), std::istreambuf_iterator<char>());
  std::map<std::string, std::vector<std::string>> scenes_of;  // method name -> scene files using it
  for (const auto& entry : std::filesystem::directory_iterator(LUCENT_SCENES_DIR)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path());
    const nlohmann::json scene = nlohmann::json::parse(in, nullptr, false, true);
    ASSERT_FALSE(scene.is_discarded()) << entry.path();
    const std::string fallback(lucent::methods::default_method().name);
    const std::string method = scene.contains("method") ? scene["method"].value("name", fallback) : fallback;
    scenes_of[method].push_back(entry.path().filename().string());
  }
  for (const lucent::methods::MethodInfo* method : lucent::methods::method_registry()) {
    const auto found = scenes_of.find(std::string(method->name));
    ASSERT_NE(found, scenes_of.end()) << method->name << " has no scene in scenes/ that uses it";
    bool listed = false;
    for (const std::string& file : found->second) listed = listed || readme.find(file) != std::string::npos;
    EXPECT_TRUE(listed) << method->name << ": the README's scene table names none of " << found->second.front();
  }
}

// A material that names no model gets kDefaultBssrdfModel, and `lucent` help states that default.
TEST(SceneLoader, AMaterialWithoutAModelGetsTheDefaultModel) {
  const Scene scene = parse_scene(R"({"objects": [{"shape": "sphere", "material": {"sigma_a": [0.01, 0.02, 0.03],
      "sigma_s": [1, 1, 1]}}, {"shape": "sphere", "material": "Marble"}]})", "model.json", ".");
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].material->model, kDefaultBssrdfModel);
  EXPECT_EQ(scene.objects[1].material->model, kDefaultBssrdfModel);
  EXPECT_EQ(kDefaultBssrdfModel, BssrdfModel::StandardDipole);  // docs/accuracy.md, "Which model by default"
  bool stated = false;
  for (const ParamSection& section : scene_param_sections())
    for (const ParamDecl& p : section.params)
      if (p.name == "model" && section.name.find("material") != std::string_view::npos)
        stated = p.default_json == "\"" + std::string(to_string(kDefaultBssrdfModel)) + "\"";
  EXPECT_TRUE(stated) << "the material's model parameter does not declare the default model";
}

TEST(SceneLoader, ParamSectionsForHelp) {
  std::vector<ParamSection> sections = scene_param_sections();
  auto find = [&](std::string_view name) -> const ParamSection* {
    for (const ParamSection& s : sections)
      if (s.name == name) return &s;
    return nullptr;
  };
  EXPECT_NE(find("camera"), nullptr);
  EXPECT_NE(find("render"), nullptr);
  const ParamSection* method = find("radiosity-maps");
  ASSERT_NE(method, nullptr);
  std::string text = describe(*method);
  EXPECT_NE(text.find("eps_bias"), std::string::npos) << text;
  EXPECT_NE(text.find("map texels"), std::string::npos) << text;
  // The help states the bounds checked: a coefficient beyond 1e30 is refused, so it does not read [-inf, inf].
  const ParamSection* material = find("objects[].material");
  ASSERT_NE(material, nullptr);
  text = describe(*material);
  EXPECT_NE(text.find("[-1e+30, 1e+30] mm^-1"), std::string::npos) << text;
  EXPECT_EQ(text.find("inf]"), std::string::npos) << text;
}

// ---- bad inputs: exact messages -------------------------------------------------------------------

TEST(SceneLoader, MalformedJson) {
  std::string message = parse_error(std::string("{ \"objects\": [ }"));
  EXPECT_EQ(message.rfind("test.json: malformed JSON:", 0), 0u) << message;
  EXPECT_NE(message.find("line 1"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(SceneLoader, CommentsAreAllowed) {
  std::string text = "// a comment\n" + minimal_scene().dump() + "\n/* trailing */";
  EXPECT_EQ(parse_error(text), "");
}

TEST(SceneLoader, UnknownTopLevelKey) {
  json doc = minimal_scene();
  doc["objcets"] = json::array();
  EXPECT_EQ(parse_error(doc),
            "test.json: /objcets: unknown key; known keys: scale_mm, comment, camera, lights, environment, objects, method, render, denoise");
}

TEST(SceneLoader, UnknownMethodKey) {
  json doc = minimal_scene();
  doc["method"] = {{"KK", 8}};
  EXPECT_EQ(parse_error(doc),
            "test.json: /method/KK: unknown key; known keys: K, directions, map_directions, N, map_size, light_map_size, "
            "eps_bias, eps_comb, "
            "visibility_taps, filter_lod, progressive, converged_after, specular, roughness, vpls, vpl_map_size, view, name");
}

TEST(SceneLoader, NegativeSigmaA) {
  EXPECT_EQ(material_error({{"sigma_a", {-0.5, 0.1, 0.1}}, {"sigma_s", {1, 1, 1}}}),
            "test.json: /objects/0/material: sigma_a[0] = -0.5 is negative; allowed range [0, inf) mm^-1");
}

TEST(SceneLoader, NanEta) {
  EXPECT_EQ(material_error({{"preset", "Marble"}, {"eta", "nan"}}),
            "test.json: /objects/0/material/eta: NaN is not allowed; allowed range [1, 3]");
}

TEST(SceneLoader, EtaOutOfRange) {
  EXPECT_EQ(material_error({{"preset", "Marble"}, {"eta", 0.5}}),
            "test.json: /objects/0/material/eta: 0.5 is out of range; allowed range [1, 3]");
}

// A value the range check refuses is never called "any finite number": the message states the bounds checked.
TEST(SceneLoader, HugeCoefficientStatesTheBoundsChecked) {
  EXPECT_EQ(material_error({{"sigma_a", {1.4427e303, 0.1, 0.1}}, {"sigma_s", {1, 1, 1}}}),
            "test.json: /objects/0/material/sigma_a/0: 1.4427e+303 is out of range; allowed range [-1e+30, 1e+30] mm^-1");
}

TEST(SceneLoader, KZero) {
  json doc = minimal_scene();
  doc["method"] = {{"K", 0}};
  EXPECT_EQ(parse_error(doc), "test.json: /method/K: 0 is out of range; allowed range [1, 64] maps");
}

TEST(SceneLoader, MapSizeZero) {
  json doc = minimal_scene();
  doc["method"] = {{"name", "radiosity-maps"}, {"map_size", 0}};
  EXPECT_EQ(parse_error(doc), "test.json: /method/map_size: 0 is out of range; allowed range [8, 4096] texels");
}

TEST(SceneLoader, MissingMeshFile) {
  json doc = minimal_scene();
  doc["objects"][0] = {{"mesh", "meshes/missing.obj"}};
  EXPECT_EQ(parse_error(doc),
            "test.json: /objects/0/mesh: /nonexistent/scene/dir/meshes/missing.obj: no such file");
}

TEST(SceneLoader, UnknownPreset) {
  EXPECT_EQ(material_error("Unobtainium"),
            "test.json: /objects/0/material/preset: unknown material 'Unobtainium' (see: lucent materials)");
}

TEST(SceneLoader, PresetAndCoefficients) {
  EXPECT_EQ(material_error({{"preset", "Marble"}, {"sigma_a", {0.1, 0.1, 0.1}}}),
            "test.json: /objects/0/material: give either preset or coefficients, not both");
}

TEST(SceneLoader, SigmaSAndSigmaSPrime) {
  EXPECT_EQ(material_error({{"sigma_a", {0.1, 0.1, 0.1}}, {"sigma_s", {1, 1, 1}}, {"sigma_s_prime", {1, 1, 1}}}),
            "test.json: /objects/0/material: give exactly one of sigma_s and sigma_s_prime");
}

TEST(SceneLoader, ShapeAndMesh) {
  json doc = minimal_scene();
  doc["objects"][0]["mesh"] = "bunny.obj";
  EXPECT_EQ(parse_error(doc), "test.json: /objects/0: give exactly one of shape and mesh");
}

TEST(SceneLoader, EmptyObjects) {
  json doc = minimal_scene();
  doc["objects"] = json::array();
  EXPECT_EQ(parse_error(doc), "test.json: /objects: expected a non-empty array of objects");
}

TEST(SceneLoader, LightWithoutDirection) {
  json doc = minimal_scene();
  doc["lights"][0] = {{"radiance", {1, 1, 1}}};
  EXPECT_EQ(parse_error(doc),
            "test.json: /lights/0/direction: missing; a directional light needs it, e.g. [0, -1, 0] (the direction the "
            "light travels)");
}

TEST(SceneLoader, PointAndSpotLights) {
  json doc = minimal_scene();
  doc["scale_mm"] = 10;
  doc["lights"] = json::array({{{"type", "point"}, {"position", {0, 1, 0}}, {"intensity", {2e-3, 1e-3, 0}}},
                               {{"type", "spot"}, {"position", {0, 2, 0}}, {"direction", {0, -2, 0}},
                                {"inner_deg", 10}, {"outer_deg", 20}}});
  Scene scene = parse_scene(doc.dump(), "test.json", ".");
  ASSERT_EQ(scene.lights.size(), 0u);
  ASSERT_EQ(scene.point_lights.size(), 2u);
  EXPECT_FALSE(scene.point_lights[0].spot);
  EXPECT_TRUE(scene.point_lights[1].spot);
  EXPECT_FLOAT_EQ(scene.point_lights[1].direction.y, -1.0f);
  // 1 unit = 10 mm: 100 units per metre, so E = I / d_m^2 = I * 100^2 / d_units^2.
  EXPECT_FLOAT_EQ(intensity_in_scene_units(scene.point_lights[0], scene.scale_mm).x, 20.0f);
}

TEST(SceneLoader, LightKeysOfAnotherType) {
  json doc = minimal_scene();
  doc["lights"][0] = {{"direction", {0, -1, 0}}, {"position", {0, 1, 0}}};
  EXPECT_EQ(parse_error(doc), "test.json: /lights/0/position: not used by a directional light");
  doc["lights"][0] = {{"type", "point"}};
  EXPECT_EQ(parse_error(doc), "test.json: /lights/0/position: missing; a point light needs it, e.g. [0, 1, 0]");
  doc["lights"][0] = {{"type", "point"}, {"position", {0, 1, 0}}, {"direction", {0, -1, 0}}};
  EXPECT_EQ(parse_error(doc), "test.json: /lights/0/direction: not used by a point light");
  doc["lights"][0] = {{"type", "spot"}, {"position", {0, 1, 0}}, {"direction", {0, -1, 0}}, {"inner_deg", 50},
                      {"outer_deg", 40}};
  EXPECT_EQ(parse_error(doc), "test.json: /lights/0/inner_deg: 50 exceeds outer_deg 40");
}

TEST(SceneLoader, LatheProfileErrors) {
  json doc = minimal_scene();
  doc["objects"][0] = {{"shape", "lathe"}, {"profile", {{0, 0}, {1, 0}}}, {"material", "Marble"}};
  EXPECT_EQ(parse_error(doc), "test.json: /objects/0/profile: lathe needs a profile of at least 3 [r, y] points");
  doc["objects"][0]["profile"] = {{0, 0}, {-1, 0}, {1, 1}};
  EXPECT_EQ(parse_error(doc), "test.json: /objects/0/profile/1: [-1, 0]: r must be >= 0 and both finite");
  doc["objects"][0] = {{"shape", "sphere"}, {"profile", {{0, 0}, {1, 0}, {1, 1}}}, {"material", "Marble"}};
  EXPECT_EQ(parse_error(doc), "test.json: /objects/0/profile: only used by shape lathe");
  doc["objects"][0] = {{"shape", "shell"}, {"radius", 1}, {"inner_radius", 1.5}, {"material", "Marble"}};
  EXPECT_EQ(parse_error(doc), "test.json: /objects/0/inner_radius: 1.5 must be smaller than radius 1");
}

TEST(SceneLoader, EnvironmentBecomesDirectionalLights) {
  json doc = minimal_scene();
  doc["environment"] = {{"file", "env/sky.hdr"}, {"lights", 8}, {"intensity", 2.0}};
  Scene scene = parse_scene(doc.dump(), "test.json", LUCENT_SCENES_DIR);
  ASSERT_TRUE(scene.environment.has_value());
  EXPECT_EQ(scene.lights.size(), 1u + 8u);  // the scene's own light, then the map's
  EXPECT_TRUE(scene.lights[0].specular);
  glm::vec3 total(0.0f);
  for (std::size_t i = 1; i < scene.lights.size(); ++i) {
    EXPECT_FALSE(scene.lights[i].specular);
    total += scene.lights[i].radiance;
  }
  // The lights carry the (scaled) map's whole power.
  glm::vec3 power = lucent::environment_power(*scene.environment->map);
  EXPECT_NEAR(total.x / power.x, 1.0, 1e-4);
  doc["environment"] = {{"file", "env/none.hdr"}};
  std::string error = test::error_message([&] { parse_scene(doc.dump(), "test.json", LUCENT_SCENES_DIR); });
  EXPECT_EQ(error.rfind("test.json: /environment/file: ", 0), 0u) << error;
}

TEST(SceneLoader, Vec3ListParameter) {
  json doc = minimal_scene();
  doc["method"] = {{"map_directions", {{0, 0, 1}, {1, 0, 0}}}};
  Scene scene = parse_scene(doc.dump(), "test.json", ".");
  ASSERT_EQ(scene.method_params.vec3_list("map_directions").size(), 2u);
  EXPECT_EQ(scene.method_params.vec3_list("map_directions")[1], glm::vec3(1, 0, 0));
  doc["method"] = {{"map_directions", {{0, 0}}}};
  EXPECT_EQ(parse_error(doc), "test.json: /method/map_directions/0: expected an array of 3 numbers, got [0,0]");
  doc["method"] = {{"map_directions", {0, 0, 1}}};
  EXPECT_EQ(parse_error(doc), "test.json: /method/map_directions/0: expected an array of 3 numbers, got 0");
}

TEST(SceneLoader, LightZeroDirection) {
  json doc = minimal_scene();
  doc["lights"][0]["direction"] = {0, 0, 0};
  EXPECT_EQ(parse_error(doc), "test.json: /lights/0/direction: must be a non-zero vector");
}

TEST(SceneLoader, UnknownMethod) {
  json doc = minimal_scene();
  doc["method"] = {{"name", "photon-beams"}};
  std::string known;  // every registered method, in registry order
  for (const lucent::methods::MethodInfo* m : lucent::methods::method_registry())
    known += (known.empty() ? "" : ", ") + std::string(m->name);
  EXPECT_EQ(known.rfind("radiosity-maps, per-pixel, voxel-paths, texture-space-is, hybrid", 0), 0u) << known;
  EXPECT_EQ(parse_error(doc), "test.json: /method/name: unknown method 'photon-beams'; known: " + known);
}

TEST(SceneLoader, WrongType) {
  json doc = minimal_scene();
  doc["render"] = {{"width", "abc"}};
  EXPECT_EQ(parse_error(doc), "test.json: /render/width: expected a number, got \"abc\"");
}

TEST(SceneLoader, OverrideBadIndex) {
  EXPECT_EQ(parse_error(minimal_scene(), {"objects.9.shape=box"}), "--set 'objects.9.shape=box': index 9 out of range (1 elements)");
}

TEST(SceneLoader, OverrideIntoStringShorthand) {
  // A material given as a preset's name stands for {"preset": name}: a key below it can be set.
  const Scene scene = parse(minimal_scene(), {"objects.0.material.eta=1.4"});
  ASSERT_TRUE(scene.objects[0].material);
  EXPECT_EQ(scene.objects[0].material->name, "Marble");
  EXPECT_FLOAT_EQ(scene.objects[0].material->eta, 1.4f);
  EXPECT_EQ(parse_error(minimal_scene(), {"objects.0.shape.size=2"}),
            "--set 'objects.0.shape.size=2': cannot set 'size' inside \"sphere\" (not an object)");
}

TEST(SceneLoader, OverrideElementByName) {
  json doc = minimal_scene();
  doc["objects"].push_back(json{{"name", "ball"}, {"shape", "sphere"}, {"material", "Marble"}});
  const Scene scene = parse(doc, {"objects.ball.material=Ketchup"});
  ASSERT_TRUE(scene.objects[1].material && scene.objects[0].material);
  EXPECT_EQ(scene.objects[1].material->name, "Ketchup");
  EXPECT_EQ(scene.objects[0].material->name, "Marble");
  EXPECT_EQ(parse_error(doc, {"objects.bunny.material=Ketchup"}),
            "--set 'objects.bunny.material=Ketchup': 'bunny' is neither an index nor the name of an element of "
            "/objects");
}

TEST(SceneLoader, OverrideWithoutEquals) {
  EXPECT_EQ(parse_error(minimal_scene(), {"method.K"}), "--set 'method.K': expected key.path=value, e.g. method.K=8");
}

TEST(SceneLoader, LoadMissingFile) {
  const std::string path = "/nonexistent/lucent/scene.json";
  try {
    load_scene(path);
    ADD_FAILURE() << "load_scene accepted a missing file";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()), "/nonexistent/lucent/scene.json: cannot open scene file");
  }
}

TEST(SceneLoader, LoadDirectoryIsNamedADirectory) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "lucent_scene_loader_a_directory.json";
  std::filesystem::create_directories(dir);
  try {
    load_scene(dir.string());
    ADD_FAILURE() << "load_scene accepted a directory";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()), dir.string() + ": is a directory; give a scene file (JSON)");
  }
  std::filesystem::remove(dir);
}

}  // namespace
}  // namespace lucent

namespace {

// The light table's limits are errors that name the scene, not silently dropped lights.
TEST(LightViews, TooManyLightsOrLayersAreErrors) {
  using namespace lucent;
  Scene scene = parse_scene(R"({"objects": [{"shape": "sphere", "material": "Marble"}]})", "lights.json", ".");
  render::BoundingSphere object{{0, 0, 0}, 1.0f}, all{{0, 0, 0}, 10.0f};
  for (int i = 0; i < 10; ++i) scene.point_lights.push_back({glm::vec3(5.0f + static_cast<float>(i), 0, 0)});
  auto build = [&] { render::build_light_views(scene, object, all, 64); };
  std::string message = test::error_message(build);
  EXPECT_EQ(message, "lights.json: the lights need 70 light G-buffer layers; at most 64 are supported (a directional "
                     "light needs 2, a point or spot light 6 or 7)");
  scene.point_lights.resize(17);
  message = test::error_message(build);
  EXPECT_EQ(message, "lights.json: 17 lights; at most 16 are supported");
  // Inside the objects' bounding sphere: one shared cube map (6 layers); outside: a frustum and a cube (7).
  scene.point_lights = {PointLight{}, PointLight{glm::vec3(5, 0, 0)}};
  render::LightViews views = render::build_light_views(scene, object, all, 64);
  ASSERT_EQ(views.lights.size(), 2u);
  EXPECT_EQ(views.lights[0].views, glm::ivec4(0, 6, 0, 6));
  EXPECT_EQ(views.lights[1].views, glm::ivec4(6, 1, 7, 6));
}

}  // namespace

// The denoising stage's section: off by default, its values read as declared (denoise/denoise_params.h), refused
// outside their ranges with one line naming the key.
TEST(SceneLoader, DenoiseSection) {
  EXPECT_FALSE(lucent::denoise::denoise_settings(parse(minimal_scene()).denoise).enabled);
  json doc = minimal_scene();
  doc["denoise"] = {{"enabled", true}, {"iterations", 3}, {"fade_frames", 0}};
  const lucent::denoise::DenoiseSettings s = lucent::denoise::denoise_settings(parse(doc).denoise);
  EXPECT_TRUE(s.enabled);
  EXPECT_EQ(s.iterations, 3);
  EXPECT_EQ(s.fade_frames, 0.0f);
  EXPECT_EQ(s.sigma_luminance, 8.0f);  // the default
  EXPECT_TRUE(lucent::denoise::denoise_settings(parse(minimal_scene(), {"denoise.enabled=true"}).denoise).enabled);
  doc["denoise"] = {{"iterations", 9}};
  EXPECT_NE(parse_error(doc).find("test.json: /denoise/iterations"), std::string::npos) << parse_error(doc);
  doc["denoise"] = {{"sigma_luminanse", 2}};
  EXPECT_NE(parse_error(doc).find("/denoise/sigma_luminanse: unknown key"), std::string::npos) << parse_error(doc);
  doc["denoise"] = 1;
  EXPECT_NE(parse_error(doc).find("/denoise"), std::string::npos) << parse_error(doc);
}
