// test_precompute_runner.cpp: a method's precompute step (PrecomputeDecl) through the cache, with a test-local
// declaration: progress is non-decreasing in [0, 1] and ends with one 1 whatever the step reports; the bytes are
// stored and read back instead of computed again; the key follows meshes, materials, method parameters, kind,
// version and the atlas, not lights; a disabled cache computes every time and writes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "../temp_cache_dir.h"
#include "lucent/lucent.h"
#include "methods/precompute.h"
#include "texture_space/scene_atlas.h"

namespace {

using lucent::methods::PrecomputeDecl;
using lucent::methods::PrecomputeInput;
using lucent::test::TempCacheDir;

int g_computed = 0;  // calls of the test step

// Reports an unruly sequence (a step back, a value past 1, NaN) and returns bytes naming its inputs.
std::vector<std::byte> test_step(const PrecomputeInput& input, const std::function<void(double)>& progress) {
  ++g_computed;
  for (double f : {0.1, 0.4, 0.3, std::nan(""), 0.8, 1.5, 0.9}) progress(f);
  std::string text = input.scene.method + ":" + std::to_string(input.scene.objects.size()) + ":" +
                     std::to_string(input.atlas ? input.atlas->atlas.size : 0);
  const auto* data = reinterpret_cast<const std::byte*>(text.data());
  return {data, data + text.size()};
}

constexpr PrecomputeDecl kTestStep{"test-precompute", 3, test_step};

lucent::Scene scene() {
  return lucent::parse_scene(R"({
    "method": { "name": "per-pixel" },
    "lights": [ { "direction": [0.5, -0.6, -0.62], "radiance": [3.0, 3.0, 3.0] } ],
    "objects": [
      { "name": "ball", "shape": "sphere", "radius": 0.5, "material": "Marble" },
      { "name": "floor", "shape": "plane", "extent": [4, 4], "albedo": [0.5, 0.5, 0.5] }
    ]})", "precompute.json", ".");
}

class PrecomputeRunner : public ::testing::Test {
 protected:
  void SetUp() override { g_computed = 0; }
  TempCacheDir dir_;
};

TEST_F(PrecomputeRunner, ProgressIsNonDecreasingAndEndsAtOne) {
  lucent::Scene s = scene();
  std::vector<double> fractions;
  auto record = [&](double f) { fractions.push_back(f); };
  lucent::methods::run_precompute(kTestStep, {s}, record);
  ASSERT_GE(fractions.size(), 3u);
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  for (std::size_t i = 1; i < fractions.size(); ++i) {
    EXPECT_GE(fractions[i], fractions[i - 1]) << "at " << i;
    EXPECT_LE(fractions[i], 1.0);
  }
  EXPECT_EQ(std::count(fractions.begin(), fractions.end(), 1.0), 1);
  // A cache hit: 0 and 1 at once.
  fractions.clear();
  lucent::methods::run_precompute(kTestStep, {s}, record);
  EXPECT_EQ(fractions, (std::vector<double>{0.0, 1.0}));
}

TEST_F(PrecomputeRunner, BytesAreCachedAndReadBack) {
  lucent::Scene s = scene();
  lucent::methods::PrecomputeResult first = lucent::methods::run_precompute(kTestStep, {s});
  EXPECT_FALSE(first.from_cache);
  EXPECT_EQ(g_computed, 1);
  EXPECT_EQ(dir_.entry_count(), 1u);
  EXPECT_TRUE(std::filesystem::exists(lucent::cache::entry_path(lucent::methods::precompute_key(kTestStep, {s}))));
  EXPECT_NE(lucent::cache::entry_path(lucent::methods::precompute_key(kTestStep, {s})).string().find("test-precompute"),
            std::string::npos);
  lucent::methods::PrecomputeResult second = lucent::methods::run_precompute(kTestStep, {s});
  EXPECT_TRUE(second.from_cache);
  EXPECT_EQ(g_computed, 1);
  EXPECT_EQ(second.bytes, first.bytes);
  EXPECT_FALSE(second.bytes.empty());
}

TEST_F(PrecomputeRunner, KeyFollowsItsInputs) {
  lucent::Scene s = scene();
  const lucent::cache::Digest key = lucent::methods::precompute_key(kTestStep, {s}).digest();
  auto differs = [&](const lucent::Scene& other) {
    return lucent::methods::precompute_key(kTestStep, {other}).digest() != key;
  };
  lucent::Scene mesh = s;
  mesh.objects[0].mesh.normals[2].z = -mesh.objects[0].mesh.normals[2].z;
  EXPECT_TRUE(differs(mesh));
  lucent::Scene material = s;
  material.objects[0].material->sigma_s.x *= 1.01f;
  EXPECT_TRUE(differs(material));
  lucent::Scene albedo = s;
  albedo.objects[1].albedo.y = 0.25f;
  EXPECT_TRUE(differs(albedo));
  lucent::Scene moved = s;
  moved.objects[1].world_from_object[3][2] = 1.0f;
  EXPECT_TRUE(differs(moved));
  lucent::Scene param = s;
  param.method_params.set("test_only", lucent::ParamValue(2.0));
  EXPECT_TRUE(differs(param));
  lucent::Scene scale = s;
  scale.scale_mm *= 2.0f;
  EXPECT_TRUE(differs(scale));
  PrecomputeDecl other_kind = kTestStep, other_version = kTestStep;
  other_kind.kind = "test-precompute-b";
  other_version.version = 4;
  EXPECT_NE(lucent::methods::precompute_key(other_kind, {s}).digest(), key);
  EXPECT_NE(lucent::methods::precompute_key(other_version, {s}).digest(), key);
  // The atlas: its size and charts.
  lucent::texture_space::SceneAtlas atlas = lucent::texture_space::build_scene_atlas(s, {.size = 128});
  const lucent::cache::Digest with_atlas = lucent::methods::precompute_key(kTestStep, {s, &atlas}).digest();
  EXPECT_NE(with_atlas, key);
  atlas.atlas.objects[0].chart[0] += 1;
  EXPECT_NE(lucent::methods::precompute_key(kTestStep, {s, &atlas}).digest(), with_atlas);
  // Lights and the camera are no input.
  lucent::Scene lit = s;
  lit.camera.eye.x += 1.0f;
  ASSERT_FALSE(lit.lights.empty());
  lit.lights.clear();
  EXPECT_FALSE(differs(lit));
}

TEST_F(PrecomputeRunner, DisabledCacheComputesEveryTimeAndWritesNothing) {
  lucent::Scene s = scene();
  lucent::cache::set_enabled(false);
  EXPECT_FALSE(lucent::methods::run_precompute(kTestStep, {s}).from_cache);
  EXPECT_FALSE(lucent::methods::run_precompute(kTestStep, {s}).from_cache);
  EXPECT_EQ(g_computed, 2);
  EXPECT_EQ(dir_.entry_count(), 0u);
}

}  // namespace
