// test_atlas_cache.cpp: the scene atlas through the precompute cache: bytes round trip exactly, the second
// load_or_build_scene_atlas reads the first one back, a changed mesh, transform or option misses, a disabled
// cache builds and writes nothing, bytes that are not an atlas are refused, and `lucent atlas` says "(cached)"
// and honours --no-cache.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "../cli_runner.h"
#include "../temp_cache_dir.h"
#include "../test_support.h"
#include "lucent/lucent.h"
#include "texture_space/atlas_encoding.h"
#include "texture_space/scene_atlas_cache.h"
#include "../test_paths.h"

namespace {

using namespace lucent::texture_space;
using lucent::test::TempCacheDir;

lucent::Scene ball_floor_ring_scene() {
  return lucent::parse_scene(R"({
    "objects": [
      { "name": "ball", "shape": "sphere", "radius": 0.5, "material": "Marble" },
      { "name": "floor", "shape": "plane", "extent": [4, 4], "albedo": [0.5, 0.5, 0.5] },
      { "name": "ring", "shape": "torus", "major_radius": 0.8, "minor_radius": 0.3, "translate": [2, 0, 0],
        "material": "Potato" }
    ]})", "two.json", ".");
}

void expect_same_mesh(const lucent::TriangleMesh& a, const lucent::TriangleMesh& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(a.uvs, b.uvs);
}

// Field by field, then the encodings (which cover every field, metrics bit for bit).
void expect_same_atlas(const SceneAtlas& a, const SceneAtlas& b) {
  EXPECT_EQ(a.atlas.size, b.atlas.size);
  ASSERT_EQ(a.atlas.objects.size(), b.atlas.objects.size());
  for (std::size_t k = 0; k < a.atlas.objects.size(); ++k) {
    expect_same_mesh(a.atlas.objects[k].mesh, b.atlas.objects[k].mesh);
    EXPECT_EQ(a.atlas.objects[k].source_vertex, b.atlas.objects[k].source_vertex);
    EXPECT_EQ(a.atlas.objects[k].chart, b.atlas.objects[k].chart);
  }
  EXPECT_EQ(a.atlas.metrics.chart_count, b.atlas.metrics.chart_count);
  EXPECT_EQ(a.atlas.metrics.utilization, b.atlas.metrics.utilization);
  EXPECT_EQ(a.atlas.metrics.stretch_l2, b.atlas.metrics.stretch_l2);
  EXPECT_EQ(a.atlas.metrics.build_ms, b.atlas.metrics.build_ms);
  EXPECT_EQ(a.atlas.metrics.texel_size, b.atlas.metrics.texel_size);
  EXPECT_EQ(a.object_index, b.object_index);
  EXPECT_EQ(a.own_uvs, b.own_uvs);
  EXPECT_EQ(a.own_uv_problem, b.own_uv_problem);
  EXPECT_EQ(encode_scene_atlas(a), encode_scene_atlas(b));
}

TEST(AtlasCache, BytesRoundTripExactly) {
  SceneAtlas built = build_scene_atlas(ball_floor_ring_scene(), {.size = 256});
  ASSERT_EQ(built.atlas.objects.size(), 2u);
  SceneAtlas back = decode_scene_atlas(encode_scene_atlas(built));
  expect_same_atlas(built, back);

  // The single-object case with the mesh's own coordinates, and a refused-own-coordinates note.
  lucent::Scene one;
  one.source = "one.json";
  lucent::SceneObject object;
  object.name = "torus";
  object.mesh = lucent::make_torus(1.0f, 0.4f, 12, 24);
  object.material = lucent::Material{};
  one.objects.push_back(object);
  SceneAtlas own = build_scene_atlas(one, {.size = 128});
  ASSERT_TRUE(own.own_uvs);
  expect_same_atlas(own, decode_scene_atlas(encode_scene_atlas(own)));
  one.objects[0].mesh.uvs[0] = {1.5f, 0.5f};
  SceneAtlas noted = build_scene_atlas(one, {.size = 128});
  ASSERT_FALSE(noted.own_uv_problem.empty());
  expect_same_atlas(noted, decode_scene_atlas(encode_scene_atlas(noted)));
}

TEST(AtlasCache, BytesThatAreNotAnAtlasAreRefused) {
  std::vector<std::byte> bytes = encode_scene_atlas(build_scene_atlas(ball_floor_ring_scene(), {.size = 128}));
  for (std::size_t cut : {std::size_t{0}, std::size_t{3}, bytes.size() / 2, bytes.size() - 1}) {
    std::string message = lucent::test::error_message([&] { decode_scene_atlas(std::span(bytes).first(cut)); });
    EXPECT_EQ(message.rfind("scene atlas: ", 0), 0u) << "cut at " << cut << ": " << message;
  }
  std::vector<std::byte> longer = bytes;
  longer.push_back(std::byte{0});
  EXPECT_EQ(lucent::test::error_message([&] { decode_scene_atlas(longer); }),
            "scene atlas: trailing bytes after the encoded atlas");
  std::vector<std::byte> other_version = bytes;
  other_version[4] = std::byte{99};
  EXPECT_EQ(lucent::test::error_message([&] { decode_scene_atlas(other_version); }),
            "scene atlas: encoding version 99, this build reads 1");
}

TEST(AtlasCache, SecondLoadComesFromTheCacheAndEqualsTheFirst) {
  TempCacheDir dir;
  lucent::Scene scene = ball_floor_ring_scene();
  std::vector<double> fractions;
  CachedSceneAtlas first = load_or_build_scene_atlas(scene, {.size = 256}, [&](double f) { fractions.push_back(f); });
  EXPECT_FALSE(first.from_cache);
  EXPECT_EQ(fractions, (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(dir.entry_count(), 1u);
  EXPECT_TRUE(std::filesystem::exists(lucent::cache::entry_path(atlas_cache_key(scene, {.size = 256}))));
  CachedSceneAtlas second = load_or_build_scene_atlas(scene, {.size = 256});
  EXPECT_TRUE(second.from_cache);
  expect_same_atlas(first.atlas, second.atlas);
  EXPECT_EQ(dir.entry_count(), 1u);
}

TEST(AtlasCache, ChangedMeshTransformOrOptionMisses) {
  TempCacheDir dir;
  lucent::Scene scene = ball_floor_ring_scene();
  ASSERT_FALSE(load_or_build_scene_atlas(scene, {.size = 256}).from_cache);
  ASSERT_TRUE(load_or_build_scene_atlas(scene, {.size = 256}).from_cache);
  EXPECT_FALSE(load_or_build_scene_atlas(scene, {.size = 512}).from_cache);
  EXPECT_FALSE(load_or_build_scene_atlas(scene, {.size = 256, .cone_deg = 25.0f}).from_cache);
  EXPECT_FALSE(load_or_build_scene_atlas(scene, {.size = 256, .border_texels = 4}).from_cache);
  lucent::Scene moved = scene;
  moved.objects[0].world_from_object[3][0] += 0.25f;
  EXPECT_FALSE(load_or_build_scene_atlas(moved, {.size = 256}).from_cache);
  lucent::Scene edited = scene;
  edited.objects[2].mesh.positions[5].y += 1e-4f;
  CachedSceneAtlas rebuilt = load_or_build_scene_atlas(edited, {.size = 256});
  EXPECT_FALSE(rebuilt.from_cache);
  EXPECT_EQ(rebuilt.atlas.atlas.objects[1].mesh.positions, build_scene_atlas(edited, {.size = 256}).atlas.objects[1].mesh.positions);
  // An opaque object's mesh is not an input of the atlas.
  lucent::Scene floor_edited = scene;
  floor_edited.objects[1].mesh.positions[0].y += 1.0f;
  EXPECT_TRUE(load_or_build_scene_atlas(floor_edited, {.size = 256}).from_cache);
}

TEST(AtlasCache, DisabledCacheBuildsAndWritesNothing) {
  TempCacheDir dir;
  lucent::Scene scene = ball_floor_ring_scene();
  lucent::cache::set_enabled(false);
  EXPECT_FALSE(load_or_build_scene_atlas(scene, {.size = 256}).from_cache);
  EXPECT_FALSE(load_or_build_scene_atlas(scene, {.size = 256}).from_cache);
  EXPECT_EQ(dir.entry_count(), 0u);
  lucent::cache::set_enabled(true);
  EXPECT_FALSE(load_or_build_scene_atlas(scene, {.size = 256}).from_cache);
  EXPECT_TRUE(load_or_build_scene_atlas(scene, {.size = 256}).from_cache);
}

TEST(AtlasCache, BlobSurfacesAreRefusedBeforeTheCache) {
  TempCacheDir dir;
  lucent::Scene scene = lucent::load_scene(std::string(LUCENT_SCENES_DIR) + "/blobs.json");
  std::string message = lucent::test::error_message([&] { load_or_build_scene_atlas(scene, {}); });
  EXPECT_NE(message.find("a blob surface has no stable texture parameterisation"), std::string::npos) << message;
  EXPECT_EQ(dir.entry_count(), 0u);
}

TEST(CliAtlas, SecondRunIsCachedAndNoCacheNeverWrites) {
  TempCacheDir dir;
  std::string env = "LUCENT_CACHE_DIR=" + dir.path().string();
  lucent::test::CliResult no_cache = lucent::test::run_cli("atlas --size 128 --no-cache", env);
  ASSERT_EQ(no_cache.exit_code, 0) << no_cache.output;
  EXPECT_EQ(no_cache.output.find("(cached)"), std::string::npos) << no_cache.output;
  EXPECT_EQ(dir.entry_count(), 0u);
  lucent::test::CliResult first = lucent::test::run_cli("atlas --size 128", env);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_EQ(first.output.find("(cached)"), std::string::npos) << first.output;
  EXPECT_EQ(dir.entry_count(), 1u);
  lucent::test::CliResult second = lucent::test::run_cli("atlas --size 128", env);
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find(" ms (cached)\n"), std::string::npos) << second.output;
  lucent::test::CliResult json = lucent::test::run_cli("atlas --size 128 --json", env);
  EXPECT_NE(json.output.find("\"cached\": true"), std::string::npos) << json.output;
}

}  // namespace
