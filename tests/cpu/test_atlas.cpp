// test_atlas.cpp: texture atlases (src/texture_space/atlas.h): no overlaps, borders between charts, coordinates in
// [0, 1]^2, distortion of orthographic charts (exactly none on planar faces), the checks of a mesh's own
// coordinates, the scene atlas and its refusal of blob surfaces, and dilation.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "lucent/lucent.h"
#include "texture_space/dilate.h"
#include "texture_space/scene_atlas.h"
#include "texture_space/uv_raster.h"
#include "../test_paths.h"

namespace {

using lucent::TriangleMesh;
using namespace lucent::texture_space;

const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

// Every coordinate in [0, 1]^2, and no grid centre (2 size x 2 size) strictly inside two triangles of any object.
void expect_no_overlap(const Atlas& atlas) {
  const int grid = 2 * atlas.size;
  std::vector<int> owner(static_cast<std::size_t>(grid) * static_cast<std::size_t>(grid), 0);
  int overlaps = 0;
  for (const AtlasObject& object : atlas.objects) {
    for (glm::vec2 uv : object.mesh.uvs) {
      ASSERT_GE(uv.x, 0.0f);
      ASSERT_LE(uv.x, 1.0f);
      ASSERT_GE(uv.y, 0.0f);
      ASSERT_LE(uv.y, 1.0f);
    }
    const TriangleMesh& m = object.mesh;
    for (std::size_t f = 0; f < m.indices.size() / 3; ++f)
      for_each_cell_inside(m.uvs[m.indices[3 * f]], m.uvs[m.indices[3 * f + 1]], m.uvs[m.indices[3 * f + 2]], grid, 1e-6,
                           [&](int x, int y) { overlaps += owner[static_cast<std::size_t>(y * grid + x)]++ > 0; });
  }
  EXPECT_EQ(overlaps, 0);
}

// Each triangle's texel bounding box (a superset of the texels whose square it touches) labelled with its chart:
// texels of two different charts are at least border + 1 apart along x or y (border empty texels between).
void expect_chart_borders(const Atlas& atlas, int border) {
  const int n = atlas.size;
  std::vector<int> label(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), -1);
  int shared = 0;
  for (const AtlasObject& object : atlas.objects) {
    const TriangleMesh& m = object.mesh;
    for (std::size_t f = 0; f < object.chart.size(); ++f) {
      glm::vec2 a = m.uvs[m.indices[3 * f]], b = m.uvs[m.indices[3 * f + 1]], c = m.uvs[m.indices[3 * f + 2]];
      // Texel x touches coordinate X (in texels) when x <= X <= x + 1.
      glm::ivec2 lo = glm::ivec2(glm::ceil(glm::min(a, glm::min(b, c)) * static_cast<float>(n))) - 1;
      glm::ivec2 hi = glm::ivec2(glm::floor(glm::max(a, glm::max(b, c)) * static_cast<float>(n)));
      for (int y = std::max(0, lo.y); y <= std::min(n - 1, hi.y); ++y)
        for (int x = std::max(0, lo.x); x <= std::min(n - 1, hi.x); ++x) {
          int& l = label[static_cast<std::size_t>(y * n + x)];
          shared += l >= 0 && l != static_cast<int>(object.chart[f]);
          l = static_cast<int>(object.chart[f]);
        }
    }
  }
  EXPECT_EQ(shared, 0) << "texels touched by two charts";
  int too_close = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      int l = label[static_cast<std::size_t>(y * n + x)];
      if (l < 0) continue;
      for (int dy = -border; dy <= border; ++dy)
        for (int dx = -border; dx <= border; ++dx) {
          int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= n || ny >= n) continue;
          int other = label[static_cast<std::size_t>(ny * n + nx)];
          too_close += other >= 0 && other != l;
        }
    }
  EXPECT_EQ(too_close, 0) << "texel pairs of different charts within " << border << " texels";
}

void expect_valid(const Atlas& atlas, const TriangleMesh& input) {
  expect_no_overlap(atlas);
  expect_chart_borders(atlas, 3);
  // Positions and normals per corner are the input's (split, never moved or recomputed).
  const AtlasObject& object = atlas.objects.front();
  ASSERT_EQ(object.mesh.indices.size(), input.indices.size());
  for (std::size_t c = 0; c < input.indices.size(); ++c) {
    std::uint32_t source = object.source_vertex[object.mesh.indices[c]];
    EXPECT_EQ(source, input.indices[c]);
    EXPECT_EQ(object.mesh.positions[object.mesh.indices[c]], input.positions[source]);
    EXPECT_EQ(object.mesh.normals[object.mesh.indices[c]], input.normals[source]);
  }
  EXPECT_GT(atlas.metrics.utilization, 0.0);
  EXPECT_LE(atlas.metrics.utilization, 1.0);
}

TEST(Atlas, BoxIsSixUndistortedCharts) {
  TriangleMesh box = lucent::make_box({1.0f, 2.0f, 0.5f});
  Atlas atlas = build_atlas(box, {.size = 256});
  expect_valid(atlas, box);
  EXPECT_EQ(atlas.metrics.chart_count, 6);
  // Orthographic projection of a planar face is an isometry up to the atlas scale.
  EXPECT_NEAR(atlas.metrics.stretch_l2, 1.0, 1e-5);
  EXPECT_NEAR(atlas.metrics.stretch_max, 1.0, 1e-5);
  EXPECT_NEAR(atlas.metrics.angle_max, 1.0, 1e-5);
}

TEST(Atlas, PlaneIsOneUndistortedChart) {
  TriangleMesh plane = lucent::make_plane({3.0f, 1.0f});
  Atlas atlas = build_atlas(plane, {.size = 128});
  expect_valid(atlas, plane);
  EXPECT_EQ(atlas.metrics.chart_count, 1);
  EXPECT_NEAR(atlas.metrics.stretch_l2, 1.0, 1e-5);
  EXPECT_NEAR(atlas.metrics.angle_max, 1.0, 1e-5);
  EXPECT_GT(atlas.metrics.utilization, 0.25) << "a 3:1 rectangle fills a third of a square atlas, less its border";
}

// The default 30 degree cone bounds a triangle's stretch by 1 / cos 30 = 1.155 in one direction (1 in the other).
void expect_cone_bounds(const Atlas& atlas) {
  EXPECT_LE(atlas.metrics.angle_max, 1.0 / std::cos(glm::radians(30.0)) + 1e-3);
  EXPECT_LE(atlas.metrics.stretch_l2, 1.1);
  EXPECT_LE(atlas.metrics.angle_mean, 1.4);
}

TEST(Atlas, SphereAndTorusStretchWithinTheConeBound) {
  for (const TriangleMesh& mesh : {lucent::make_sphere(1.0f, 48, 96), lucent::make_torus(1.0f, 0.35f, 48, 96)}) {
    Atlas atlas = build_atlas(mesh, {.size = 512});
    expect_valid(atlas, mesh);
    expect_cone_bounds(atlas);
    EXPECT_LE(atlas.metrics.chart_count, 64);
  }
}

TEST(Atlas, BunnyStretchWithinTheConeBound) {
  if (!std::filesystem::exists(kBunny)) GTEST_SKIP() << kBunny << " missing (Debian package glmark2-data)";
  TriangleMesh bunny = lucent::load_mesh(kBunny);
  bunny.uvs.clear();
  Atlas atlas = build_atlas(bunny, {.size = 1024});
  expect_valid(atlas, bunny);
  expect_cone_bounds(atlas);
  EXPECT_LE(atlas.metrics.chart_count, 1000);
  EXPECT_GT(atlas.metrics.utilization, 0.25);
}

// Texels whose centre lies inside a triangle, counted here (not by the atlas's metrics), over all texels.
double covered_fraction(const Atlas& atlas) {
  const int n = atlas.size;
  std::vector<unsigned char> covered(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0);
  for (const AtlasObject& object : atlas.objects) {
    const TriangleMesh& m = object.mesh;
    for (std::size_t f = 0; f < m.indices.size() / 3; ++f)
      for_each_cell_inside(m.uvs[m.indices[3 * f]], m.uvs[m.indices[3 * f + 1]], m.uvs[m.indices[3 * f + 2]], n, 0.0,
                           [&](int x, int y) { covered[static_cast<std::size_t>(y * n + x)] = 1; });
  }
  return static_cast<double>(std::count(covered.begin(), covered.end(), 1)) / static_cast<double>(covered.size());
}

// Charts packed by their shapes: the bunny's 677 charts cover at least half of a 512^2 and of a 1024^2 atlas
// (measured 0.514 and 0.613; their bounding boxes packed covered 0.275 and 0.344), and more of a 256^2 one than the
// boxes did (0.289 against 0.131; 3 empty texels around each of 677 charts leave half out of reach there), with no
// texel shared by two charts and 3 empty texels between any two.
TEST(AtlasPacking, BunnyChartsCoverHalfTheTexelsWithBordersKept) {
  if (!std::filesystem::exists(kBunny)) GTEST_SKIP() << kBunny << " missing (Debian package glmark2-data)";
  TriangleMesh bunny = lucent::load_mesh(kBunny);
  bunny.uvs.clear();
  const std::pair<int, double> minimum[] = {{256, 0.25}, {512, 0.5}, {1024, 0.5}};
  for (auto [size, least] : minimum) {
    SCOPED_TRACE(size);
    Atlas atlas = build_atlas(bunny, {.size = size});
    expect_valid(atlas, bunny);
    const double covered = covered_fraction(atlas);
    EXPECT_DOUBLE_EQ(covered, atlas.metrics.utilization);
    EXPECT_GE(covered, least) << "fraction of the " << size << "^2 texels whose centre lies in a triangle";
  }
}

TEST(Atlas, NarrowerConeLowersStretch) {
  TriangleMesh sphere = lucent::make_sphere(1.0f, 32, 64);
  Atlas wide = build_atlas(sphere, {.size = 512, .cone_deg = 45.0f});
  Atlas narrow = build_atlas(sphere, {.size = 512, .cone_deg = 20.0f});
  EXPECT_LT(narrow.metrics.angle_max, 1.0 / std::cos(glm::radians(20.0)) + 1e-3);
  EXPECT_LT(narrow.metrics.stretch_l2, wide.metrics.stretch_l2);
  EXPECT_GT(narrow.metrics.chart_count, wide.metrics.chart_count);
}

TEST(Atlas, TooManyChartsForTheSizeIsAnError) {
  TriangleMesh sphere = lucent::make_sphere(1.0f, 32, 64);
  try {
    build_atlas(sphere, {.size = 16, .cone_deg = 5.0f});
    FAIL() << "expected lucent::Error";
  } catch (const lucent::Error& e) {
    EXPECT_NE(std::string(e.what()).find("do not fit into a 16 x 16 atlas with 3-texel borders"), std::string::npos) << e.what();
  }
}

// Two unit squares in [0, 1]^2 as four triangles with given texture coordinates.
TriangleMesh quad_with_uvs(std::vector<glm::vec2> uvs) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.normals.assign(4, {0, 0, 1});
  m.indices = {0, 1, 2, 0, 2, 3};
  m.uvs = std::move(uvs);
  return m;
}

TEST(AtlasOwnUvs, GoodCoordinatesPass) {
  EXPECT_EQ(uv_problem(quad_with_uvs({{0.1f, 0.1f}, {0.9f, 0.1f}, {0.9f, 0.9f}, {0.1f, 0.9f}}), 64), std::nullopt);
}

TEST(AtlasOwnUvs, ProblemsAreNamed) {
  TriangleMesh none = quad_with_uvs({});
  EXPECT_EQ(uv_problem(none, 64), "the mesh has no texture coordinates");
  EXPECT_EQ(uv_problem(quad_with_uvs({{0.1f, 0.1f}, {1.25f, 0.1f}, {0.9f, 0.9f}, {0.1f, 0.9f}}), 64),
            "texture coordinate 1 = (1.25, 0.1) lies outside [0, 1]^2");
  EXPECT_EQ(uv_problem(quad_with_uvs({{0.1f, 0.1f}, {0.5f, 0.1f}, {0.9f, 0.1f}, {0.1f, 0.9f}}), 64),
            "triangle 0 has zero area in texture space");
  // Both triangles mapped onto the same half of the square: they overlap.
  EXPECT_EQ(uv_problem(quad_with_uvs({{0.1f, 0.1f}, {0.9f, 0.1f}, {0.9f, 0.9f}, {0.9f, 0.1f}}), 8),
            "triangles 0 and 1 overlap in texture space (at u = 0.2188, v = 0.1562)");
}

TEST(AtlasOwnUvs, BuiltAtlasPassesItsOwnCheck) {
  Atlas atlas = build_atlas(lucent::make_torus(1.0f, 0.4f, 24, 48), {.size = 256});
  EXPECT_EQ(uv_problem(atlas.objects.front().mesh, 256), std::nullopt);
}

lucent::Scene two_object_scene() {
  return lucent::parse_scene(R"({
    "objects": [
      { "name": "ball", "shape": "sphere", "radius": 0.5, "material": "Marble" },
      { "name": "floor", "shape": "plane", "extent": [4, 4], "albedo": [0.5, 0.5, 0.5] },
      { "name": "ring", "shape": "torus", "major_radius": 0.8, "minor_radius": 0.3, "translate": [2, 0, 0],
        "material": "Potato" }
    ]})", "two.json", ".");
}

TEST(SceneAtlas, AllTranslucentObjectsShareOneAtlasObjectByObject) {
  lucent::Scene scene = two_object_scene();
  SceneAtlas result = build_scene_atlas(scene, {.size = 512});
  ASSERT_EQ(result.object_index, (std::vector<std::size_t>{0, 2}));
  EXPECT_FALSE(result.own_uvs);
  expect_no_overlap(result.atlas);
  expect_chart_borders(result.atlas, 3);
  // Each object's charts are consecutive ids: the ball's all come before the ring's.
  std::uint32_t ball_max = 0, ring_min = ~0u;
  for (std::uint32_t c : result.atlas.objects[0].chart) ball_max = std::max(ball_max, c);
  for (std::uint32_t c : result.atlas.objects[1].chart) ring_min = std::min(ring_min, c);
  EXPECT_LT(ball_max, ring_min);
  lucent::Scene prepared = with_atlas_meshes(scene, result);
  EXPECT_EQ(prepared.objects[0].mesh.uvs.size(), prepared.objects[0].mesh.positions.size());
  EXPECT_EQ(prepared.objects[1].mesh.positions, scene.objects[1].mesh.positions) << "opaque objects untouched";
}

TEST(SceneAtlas, CacheKeyFollowsMeshesAndOptions) {
  lucent::Scene scene = two_object_scene();
  lucent::cache::Digest key = atlas_cache_key(scene, {.size = 512}).digest();
  EXPECT_EQ(key, atlas_cache_key(scene, {.size = 512}).digest());
  EXPECT_NE(key, atlas_cache_key(scene, {.size = 1024}).digest());
  EXPECT_NE(key, atlas_cache_key(scene, {.size = 512, .cone_deg = 20.0f}).digest());
  EXPECT_NE(key, atlas_cache_key(scene, {.size = 512, .use_own_uvs = false}).digest());
  lucent::Scene moved = scene;
  moved.objects[2].world_from_object[3][1] += 0.5f;
  EXPECT_NE(key, atlas_cache_key(moved, {.size = 512}).digest());
  scene.objects[2].mesh.positions[0].x += 1e-3f;
  EXPECT_NE(key, atlas_cache_key(scene, {.size = 512}).digest());
}

TEST(SceneAtlas, BlobSurfacesAreRefused) {
  lucent::Scene scene = lucent::load_scene(std::string(LUCENT_SCENES_DIR) + "/blobs.json");
  try {
    build_scene_atlas(scene, {});
    FAIL() << "expected lucent::Error";
  } catch (const lucent::Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("blobs.json: object '"), std::string::npos) << message;
    EXPECT_NE(message.find("a blob surface has no stable texture parameterisation"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
}

TEST(Dilate, GrowsFilledTexelsByTheGivenWidth) {
  const int n = 9;
  std::vector<glm::vec4> texels(n * n, glm::vec4(0.0f));
  texels[4 * n + 4] = {1.0f, 2.0f, 3.0f, 7.0f};
  dilate(texels, n, 2);
  int filled = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      bool inside = std::abs(x - 4) <= 2 && std::abs(y - 4) <= 2;
      const glm::vec4& t = texels[static_cast<std::size_t>(y * n + x)];
      filled += t.w != 0.0f;
      if (inside) {
        EXPECT_EQ(t, glm::vec4(1.0f, 2.0f, 3.0f, 7.0f)) << x << "," << y;
      }
    }
  EXPECT_EQ(filled, 25);
}

}  // namespace
