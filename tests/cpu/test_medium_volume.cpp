// test_medium_volume.cpp: heterogeneous media from files and from the scene: a volume header and its raw grid
// load (float32 and uint8 with a range), trilinear lookup is exact at voxel centres and linear between them,
// bad files give one error naming the file, and a material's "field" parses with its units.
#include <cmath>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "lucent/medium_volume.h"
#include "lucent/scene.h"
#include "../test_support.h"
#include "../test_paths.h"

namespace lucent {
namespace {

using nlohmann::json;

void write_bytes(const std::string& path, const void* data, std::size_t bytes) {
  std::ofstream(path, std::ios::binary).write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
}

MediumVolume ramp_volume() {
  MediumVolume v;
  v.size = glm::ivec3(4, 3, 2);
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x) v.values.push_back(1.0f + static_cast<float>(x) + 10.0f * static_cast<float>(y) + 100.0f * static_cast<float>(z));
  v.max_value = v.values.back();
  return v;
}

// A field linear in each axis is reproduced exactly by trilinear interpolation between voxel centres (u = (i +
// 1/2) / n), and clamped outside the outermost centres.
TEST(MediumVolume, TrilinearIsExactOnALinearField) {
  const MediumVolume v = ramp_volume();
  auto expected = [](glm::vec3 u) {  // continuous index i = u n - 1/2, clamped to [0, n - 1]
    glm::vec3 i = glm::clamp(u * glm::vec3(4, 3, 2) - 0.5f, glm::vec3(0.0f), glm::vec3(3, 2, 1));
    return 1.0f + i.x + 10.0f * i.y + 100.0f * i.z;
  };
  EXPECT_FLOAT_EQ(v.multiplier(glm::vec3(0.125f, 0.5f, 0.25f)), 1.0f + 0.0f + 10.0f + 0.0f);  // voxel (0, 1, 0)
  EXPECT_FLOAT_EQ(v.multiplier(glm::vec3(0.875f, 5.0f / 6.0f, 0.75f)), v.max_value);        // last voxel
  for (glm::vec3 u : {glm::vec3(0.3f, 0.41f, 0.6f), glm::vec3(0.55f, 0.2f, 0.33f), glm::vec3(-0.2f, 1.3f, 0.5f),
                      glm::vec3(0.99f, 0.01f, 0.74f)})
    EXPECT_NEAR(v.multiplier(u), expected(u), 1e-4f) << u.x << " " << u.y << " " << u.z;
}

TEST(MediumVolume, SaveAndLoadRoundTrip) {
  test::TempFile header(".json");
  const MediumVolume v = ramp_volume();
  save_medium_volume(v, header.path());
  std::shared_ptr<const MediumVolume> loaded = load_medium_volume(header.path());
  EXPECT_EQ(loaded->size, v.size);
  EXPECT_EQ(loaded->values, v.values);
  EXPECT_FLOAT_EQ(loaded->max_value, 124.0f);
  std::filesystem::remove(std::filesystem::path(header.path()).replace_extension(".raw"));
}

TEST(MediumVolume, Uint8MapsOntoItsRange) {
  test::TempFile header(".json"), raw(".raw");
  const unsigned char bytes[2] = {0, 255};
  write_bytes(raw.path(), bytes, 2);
  std::ofstream(header.path()) << json{{"size", {2, 1, 1}}, {"format", "uint8"}, {"range", {0.5, 3.0}},
                                       {"data", std::filesystem::path(raw.path()).filename().string()}};
  std::shared_ptr<const MediumVolume> v = load_medium_volume(header.path());
  EXPECT_FLOAT_EQ(v->values[0], 0.5f);
  EXPECT_FLOAT_EQ(v->values[1], 3.0f);
  EXPECT_FLOAT_EQ(v->max_value, 3.0f);
  EXPECT_FLOAT_EQ(v->multiplier(glm::vec3(0.5f)), 1.75f);  // midway between the two centres
}

TEST(MediumVolume, BadFilesNameTheFileAndTheProblem) {
  test::TempFile header(".json"), raw(".raw");
  const std::string h = header.path(), data = std::filesystem::path(raw.path()).filename().string();
  auto error_for = [&](const json& j) {
    std::ofstream(h) << j.dump();
    return test::error_message([&] { load_medium_volume(h); });
  };
  const float values[2] = {1.0f, std::numeric_limits<float>::quiet_NaN()};
  write_bytes(raw.path(), values, 8);
  EXPECT_EQ(test::error_message([] { load_medium_volume("/nonexistent/volume.json"); }),
            "/nonexistent/volume.json: cannot open the volume header");
  EXPECT_EQ(error_for({{"size", {2, 1, 1}}, {"data", data}}), h + ": data: value nan at voxel (1, 0, 0) is outside [0, 1e+06]: a density multiplier m is finite, >= 0 and at most 1e+06");
  EXPECT_EQ(error_for({{"size", {3, 1, 1}}, {"data", data}}),
            h + ": data: '" + raw.path() + "' has 8 bytes, size 3x1x1 float32 needs 12");
  EXPECT_EQ(error_for({{"size", {2, 1, 1}}, {"data", data}, {"spacing", 1}}),
            h + ": unknown key \"spacing\" (size, format, range, data)");
  EXPECT_EQ(error_for({{"size", {2, 0, 1}}, {"data", data}}), h + ": size[1]: must be an integer in [1, 1024]");
  EXPECT_EQ(error_for({{"size", {2, 1, 1}}, {"data", data}, {"format", "float16"}}),
            h + ": format: 'float16' is not float32 or uint8");
  EXPECT_EQ(error_for({{"size", {2, 1, 1}}, {"data", data}, {"range", {0, 2}}}), h + ": range: only for format uint8");
  EXPECT_EQ(error_for({{"size", {2, 1, 1}}, {"data", data}, {"format", 3}}), h + ": format: must be \"float32\" or \"uint8\"");
  EXPECT_EQ(error_for({{"size", {2, 1, 1}}}), h + ": missing key \"data\" (the raw file)");
  const float negative[2] = {1.0f, -0.5f};
  write_bytes(raw.path(), negative, 8);
  EXPECT_EQ(error_for({{"size", {2, 1, 1}}, {"data", data}}),
            h + ": data: value -0.5 at voxel (1, 0, 0) is outside [0, 1e+06]: a density multiplier m is finite, >= 0 and at most 1e+06");
  // 1e20 overflowed the real-time methods' single-precision optical depths: a white column, not an opaque one.
  const float dense[4] = {1.0f, 1.0f, 1.0f, 1e20f};
  write_bytes(raw.path(), dense, 16);
  EXPECT_EQ(error_for({{"size", {2, 2, 1}}, {"data", data}}),
            h + ": data: value 1e+20 at voxel (1, 1, 0) is outside [0, 1e+06]: a density multiplier m is finite, >= 0 and at most 1e+06");
}

json scene_with_field(const json& field) {
  return json{{"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
              {"objects", json::array({json{{"shape", "sphere"},
                                            {"material", json{{"preset", "Marble"}, {"field", field}}}}})}};
}

std::string scene_error(const json& doc) {
  return test::error_message([&] { parse_scene(doc.dump(), "test.json", "."); });
}

TEST(MediumField, ParsesFromTheMaterial) {
  Scene scene = parse_scene(scene_with_field({{"type", "marble"}, {"scale_mm", 6}, {"contrast", 3}}).dump(), "test.json", ".");
  const MediumField& f = scene.objects[0].material->field;
  EXPECT_EQ(f.type, MediumFieldType::Marble);
  EXPECT_FLOAT_EQ(f.scale_mm, 6.0f);
  EXPECT_FLOAT_EQ(f.max_multiplier(), 4.0f);
  Scene plain = parse_scene(scene_with_field({{"type", "none"}}).dump(), "test.json", ".");
  EXPECT_FALSE(plain.objects[0].material->field.heterogeneous());

  test::TempFile header(".json");
  save_medium_volume(ramp_volume(), header.path());
  Scene volume = parse_scene(scene_with_field({{"type", "volume"}, {"file", header.path()}}).dump(), "test.json", ".");
  ASSERT_TRUE(volume.objects[0].material->field.volume);
  EXPECT_FLOAT_EQ(volume.objects[0].material->field.max_multiplier(), 124.0f);
  std::filesystem::remove(std::filesystem::path(header.path()).replace_extension(".raw"));
}

TEST(MediumField, BadFieldsGiveOneClearError) {
  EXPECT_EQ(scene_error(scene_with_field({{"type", "granite"}})),
            "test.json: /objects/0/material/field/type: 'granite' is not one of {none|marble|layered|volume|vdb}");
  EXPECT_EQ(scene_error(scene_with_field({{"type", "marble"}, {"scale_mm", -1}})),
            "test.json: /objects/0/material/field/scale_mm: -1 is out of range; allowed range [0.001, 1e+06] mm");
  EXPECT_EQ(scene_error(scene_with_field({{"type", "volume"}})),
            "test.json: /objects/0/material/field/file: a volume field needs the file of its JSON header");
  EXPECT_EQ(scene_error(scene_with_field({{"type", "marble"}, {"file", "x.json"}})),
            "test.json: /objects/0/material/field/file: only for types volume and vdb (type is marble)");
  EXPECT_EQ(scene_error(scene_with_field({{"type", "volume"}, {"file", "missing.json"}})),
            "./missing.json: cannot open the volume header");
  EXPECT_EQ(scene_error(scene_with_field({{"type", "marble"}, {"veins", 2}})),
            "test.json: /objects/0/material/field/veins: unknown key; known keys: type, scale_mm, contrast, file, grid, density_scale, transform");
}

}  // namespace
}  // namespace lucent

namespace lucent {
namespace {

// A deforming object's field stays where the undeformed object is: scene_at_time records the rest bounds, which
// the references use (voxel-paths uses the same, from the undeformed mesh), while the deformed mesh's own box moves.
TEST(MediumField, StaysAtTheRestBoundsOfADeformingObject) {
  const Scene scene = load_scene(std::string(LUCENT_SCENES_DIR) + "/deforming_inclusion.json");
  const Scene still = scene_at_time(scene, 0.0);
  const MediumField& rest = still.objects[0].material->field;
  const Scene bent = scene_at_time(scene, 0.75);
  const MediumField& field = bent.objects[0].material->field;
  ASSERT_TRUE(rest.has_bounds && field.has_bounds);
  EXPECT_EQ(field.bounds_lower, rest.bounds_lower);
  EXPECT_EQ(field.bounds_upper, rest.bounds_upper);
  glm::vec3 lower(1e30f), upper(-1e30f);
  for (const glm::vec3& p : transformed(bent.objects[0].mesh, bent.objects[0].world_from_object).positions)
    lower = glm::min(lower, p), upper = glm::max(upper, p);
  EXPECT_GT(glm::length(upper - field.bounds_upper) + glm::length(lower - field.bounds_lower), 0.1f);
}

}  // namespace
}  // namespace lucent
