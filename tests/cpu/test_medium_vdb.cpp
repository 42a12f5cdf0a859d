// test_medium_vdb.cpp: vdb medium fields (lucent/medium_vdb.h). Each test writes its VDB files with the OpenVDB
// C++ API, filled with a known function, and checks what the loader makes of them:
//  - object-bounds copies the active bounding box voxel for voxel (exact values, density_scale applied);
//  - vdb-world, axis-aligned: the dense grid is the VDB's own voxels plus one voxel of background around them, at
//    the world position the VDB's transform gives; rotated: BoxSampler resampling, within the trilinear error bound;
//  - every bad input gives its one line naming the file;
//  - the scene parses a vdb field, writes it back as one, and volpath through a constant VDB matches the
//    homogeneous material within 3 standard errors.
#include <cmath>
#include <fstream>
#include <limits>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include "lucent/medium_vdb.h"
#include "scene/import_guard.h"
#include "lucent/scene.h"
#include "lucent/scene_writer.h"
#include "reference/embree_scene.h"
#include "reference/integrators.h"
#include "transport/estimate.h"
#include "transport/rng.h"
#include "../cli_runner.h"
#include "../test_support.h"

namespace lucent {
namespace {

using nlohmann::json;

void write_grids(const std::string& path, const openvdb::GridPtrVec& grids) {
  openvdb::initialize();
  openvdb::io::File(path).write(grids);
}

// A float grid named `name`, active over [lower, upper] (index space), voxel value f(index).
template <class F>
openvdb::FloatGrid::Ptr float_grid(const std::string& name, openvdb::Coord lower, openvdb::Coord upper, F f,
                                   openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform()) {
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName(name);
  grid->setTransform(transform);
  auto accessor = grid->getAccessor();
  for (int z = lower.z(); z <= upper.z(); ++z)
    for (int y = lower.y(); y <= upper.y(); ++y)
      for (int x = lower.x(); x <= upper.x(); ++x) accessor.setValue(openvdb::Coord(x, y, z), f(x, y, z));
  return grid;
}

float ramp(int x, int y, int z) {
  return 1.0f + 0.125f * static_cast<float>(x) + 0.25f * static_cast<float>(y) + 0.5f * static_cast<float>(z);
}

float at(const MediumVolume& v, int x, int y, int z) {
  return v.values[static_cast<std::size_t>((z * v.size.y + y) * v.size.x + x)];
}

TEST(MediumVdb, ObjectBoundsCopiesTheActiveBox) {
  test::TempFile file(".vdb");
  auto transform = openvdb::math::Transform::createLinearTransform(0.5);  // ignored by object-bounds
  transform->postTranslate(openvdb::Vec3d(3.0, -2.0, 7.0));
  write_grids(file.path(), {float_grid("density", {-2, 0, 1}, {5, 3, 2}, ramp, transform)});
  VdbField field;
  field.file = file.path();
  field.density_scale = 2.0f;
  const VdbVolume loaded = load_medium_vdb(field);
  ASSERT_TRUE(loaded.volume);
  const MediumVolume& v = *loaded.volume;
  EXPECT_FALSE(loaded.world);
  ASSERT_EQ(v.size, glm::ivec3(8, 4, 2));
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 8; ++x) EXPECT_EQ(at(v, x, y, z), 2.0f * ramp(x - 2, y, z + 1)) << x << " " << y << " " << z;
  EXPECT_EQ(v.max_value, 2.0f * ramp(5, 3, 2));
  EXPECT_EQ(v.source, file.path());
  ASSERT_NE(vdb_field_of(loaded.volume), nullptr);
  EXPECT_EQ(vdb_field_of(loaded.volume)->grid, "density");
  // Across the object's bounds: voxel centres at (i + 1/2) / n; the ramp is linear, so trilinear is exact between.
  EXPECT_NEAR(v.multiplier(glm::vec3(0.5f, 0.5f, 0.5f)), 2.0f * (1.0f + 0.125f * 1.5f + 0.25f * 1.5f + 0.5f * 1.5f),
              1e-5f);
}

TEST(MediumVdb, VdbWorldPlacesTheVoxelsWhereTheTransformSays) {
  test::TempFile file(".vdb");
  auto transform = openvdb::math::Transform::createLinearTransform(0.25);
  transform->postTranslate(openvdb::Vec3d(1.0, 2.0, 3.0));
  write_grids(file.path(), {float_grid("smoke", {0, 0, 0}, {3, 1, 2}, ramp, transform)});
  VdbField field;
  field.file = file.path();
  field.grid = "smoke";
  field.transform = VdbTransform::VdbWorld;
  const VdbVolume loaded = load_medium_vdb(field);
  const MediumVolume& v = *loaded.volume;
  ASSERT_TRUE(loaded.world);
  // Index box [-1.5, 4.5] x [-1.5, 2.5] x [-1.5, 3.5] (one voxel of background around the active voxels).
  EXPECT_NEAR(loaded.lower.x, 1.0f - 1.5f * 0.25f, 1e-6f);
  EXPECT_NEAR(loaded.lower.y, 2.0f - 1.5f * 0.25f, 1e-6f);
  EXPECT_NEAR(loaded.lower.z, 3.0f - 1.5f * 0.25f, 1e-6f);
  EXPECT_NEAR(loaded.upper.x, 1.0f + 4.5f * 0.25f, 1e-6f);
  EXPECT_NEAR(loaded.upper.y, 2.0f + 2.5f * 0.25f, 1e-6f);
  EXPECT_NEAR(loaded.upper.z, 3.0f + 3.5f * 0.25f, 1e-6f);
  ASSERT_EQ(v.size, glm::ivec3(6, 4, 5));
  for (int z = 0; z < 5; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 6; ++x) {
        const bool active = x >= 1 && x <= 4 && y >= 1 && y <= 2 && z >= 1 && z <= 3;
        EXPECT_NEAR(at(v, x, y, z), active ? ramp(x - 1, y - 1, z - 1) : 0.0f, 1e-5f) << x << " " << y << " " << z;
      }
}

// A rotated VDB holding f(p) = 3 + x + y/2 + z/4 + x^2 at its voxel centres p (world): the dense grid resampled
// with BoxSampler and then looked up trilinearly reproduces the linear part exactly and the quadratic within the
// trilinear error bound h^2 / 4 of each of the two interpolations (f_xx = 2; h = 0.1 the voxel size).
TEST(MediumVdb, VdbWorldResamplesARotatedGrid) {
  test::TempFile file(".vdb");
  const double h = 0.1, angle = 0.5235987755982988;  // 30 degrees about z
  auto transform = openvdb::math::Transform::createLinearTransform(h);
  transform->postRotate(angle, openvdb::math::Z_AXIS);
  transform->postTranslate(openvdb::Vec3d(0.3, -0.2, 0.1));
  auto world = [&](double i, double j, double k) {  // independent of OpenVDB: scale, rotate about z, translate
    const double x = h * i, y = h * j, z = h * k;
    return glm::dvec3(std::cos(angle) * x - std::sin(angle) * y + 0.3, std::sin(angle) * x + std::cos(angle) * y - 0.2,
                      z + 0.1);
  };
  auto f = [](glm::dvec3 p) { return 3.0 + p.x + 0.5 * p.y + 0.25 * p.z + p.x * p.x; };
  write_grids(file.path(), {float_grid("density", {0, 0, 0}, {19, 19, 19}, [&](int i, int j, int k) {
                return static_cast<float>(f(world(i, j, k)));
              }, transform)});
  VdbField field;
  field.file = file.path();
  field.transform = VdbTransform::VdbWorld;
  const VdbVolume loaded = load_medium_vdb(field);
  ASSERT_TRUE(loaded.world);
  // The world box of index [-1.5, 20.5]^3 and n = round(extent / h) per axis.
  glm::dvec3 lower(1e30), upper(-1e30);
  for (int c = 0; c < 8; ++c) {
    glm::dvec3 p = world(c & 1 ? 20.5 : -1.5, c & 2 ? 20.5 : -1.5, c & 4 ? 20.5 : -1.5);
    lower = glm::min(lower, p), upper = glm::max(upper, p);
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(loaded.lower[a], lower[a], 1e-5) << a;
    EXPECT_NEAR(loaded.upper[a], upper[a], 1e-5) << a;
    EXPECT_EQ(loaded.volume->size[a], std::lround((upper[a] - lower[a]) / h)) << a;
  }
  const glm::vec3 box_lower(lower), box_extent(upper - lower);
  reference::Rng rng(5, 0);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {  // points well inside the active voxels (index 2.5 .. 16.5)
    const glm::dvec3 index(2.5 + 14.0 * rng.uniform(), 2.5 + 14.0 * rng.uniform(), 2.5 + 14.0 * rng.uniform());
    const glm::dvec3 p = world(index.x, index.y, index.z);
    const float m = loaded.volume->multiplier((glm::vec3(p) - box_lower) / box_extent);
    EXPECT_NEAR(m, f(p), 2.0 * h * h / 4.0 + 1e-4) << p.x << " " << p.y << " " << p.z;
    ++checked;
  }
  EXPECT_EQ(checked, 2000);
}

TEST(MediumVdb, BadFilesNameTheFileAndTheProblem) {
  test::TempFile file(".vdb"), text(".text.vdb");
  const std::string path = file.path();
  auto error_for = [&](const openvdb::GridPtrVec& grids, const std::string& grid = "density") {
    write_grids(path, grids);
    VdbField field;
    field.file = path;
    field.grid = grid;
    return test::error_message([&] { load_medium_vdb(field); });
  };
  auto one = [](int, int, int) { return 1.0f; };
  VdbField missing;
  missing.file = "/nonexistent/smoke.vdb";
  EXPECT_EQ(test::error_message([&] { load_medium_vdb(missing); }), "/nonexistent/smoke.vdb: cannot open the VDB file");
  std::ofstream(text.path()) << "{\"size\": [2, 2, 2]}\n";
  VdbField not_vdb;
  not_vdb.file = text.path();
  EXPECT_EQ(test::error_message([&] { load_medium_vdb(not_vdb); }),
            text.path() + ": not a VDB file (no OpenVDB magic number)");
  EXPECT_EQ(error_for({float_grid("density", {0, 0, 0}, {1, 1, 1}, one), float_grid("temperature", {0, 0, 0}, {1, 1, 1}, one)},
                      "smoke"),
            path + ": no grid 'smoke' (grids: density, temperature)");
  openvdb::Vec3SGrid::Ptr velocity = openvdb::Vec3SGrid::create();
  velocity->setName("vel");
  velocity->tree().setValue(openvdb::Coord(0, 0, 0), openvdb::Vec3s(1.0f));
  EXPECT_EQ(error_for({velocity}, "vel"), path + ": grid 'vel' holds vec3s values; a vdb field needs a float grid");
  openvdb::FloatGrid::Ptr empty = openvdb::FloatGrid::create();
  empty->setName("density");
  EXPECT_EQ(error_for({empty}), path + ": grid 'density' has no active voxels");
  EXPECT_EQ(error_for({float_grid("density", {0, 0, 0}, {3, 3, 3},
                                  [](int x, int y, int z) { return x == 1 && y == 2 && z == 3 ? -0.5f : 1.0f; })}),
            path + ": grid 'density': value -0.5 at [1, 2, 3] is not a finite m >= 0");
  EXPECT_EQ(error_for({float_grid("density", {0, 0, 0}, {1, 1, 1}, [](int x, int, int) {
              return x == 1 ? std::numeric_limits<float>::quiet_NaN() : 1.0f;
            })}),
            path + ": grid 'density': value nan at [1, 0, 0] is not a finite m >= 0");
  // A density multiplier beyond 1e6 overflowed the real-time methods' single-precision optical depths.
  EXPECT_EQ(error_for({float_grid("density", {0, 0, 0}, {1, 1, 1}, [](int x, int, int) { return x == 1 ? 2e6f : 1.0f; })}),
            path + ": grid 'density': values times density_scale 1 reach 2e+06; a density multiplier is at most 1e+06");
  openvdb::FloatGrid::Ptr wide = float_grid("density", {0, 0, 0}, {0, 0, 0}, one);
  wide->tree().setValue(openvdb::Coord(2000, 0, 0), 1.0f);
  EXPECT_EQ(error_for({wide}),
            path + ": grid 'density': active bounding box 2001x1x1 voxels is over the limit (1024 per axis, 2^27 in all)");
  openvdb::FloatGrid::Ptr big = float_grid("density", {0, 0, 0}, {0, 0, 0}, one);
  big->tree().setValue(openvdb::Coord(599, 599, 599), 1.0f);
  EXPECT_EQ(error_for({big}),
            path + ": grid 'density': active bounding box 600x600x600 voxels is over the limit (1024 per axis, 2^27 in all)");
}

// The first `count` bytes of `from` as the file `to`.
void write_prefix(const std::string& from, const std::string& to, std::size_t count) {
  std::ofstream(to, std::ios::binary) << test::read_text(from).substr(0, count);
}

TEST(MediumVdb, TruncatedFilesAreRefusedBeforeOpenVdbReadsThem) {
  test::TempFile whole(".vdb"), part(".part.vdb");
  write_grids(whole.path(), {float_grid("density", {0, 0, 0}, {39, 39, 39}, ramp)});
  const std::size_t size = test::read_text(whole.path()).size();
  ASSERT_GT(size, 5000u);
  VdbField field;
  field.file = part.path();
  auto error_for = [&](std::size_t count) {
    write_prefix(whole.path(), part.path(), count);
    return test::error_message([&] { load_medium_vdb(field); });
  };
  // The grid's descriptor (name, type, offsets) ends within the first 200 bytes; its data runs to the end.
  for (std::size_t count : {200u, 5000u, static_cast<unsigned>(size - 1)})
    EXPECT_EQ(error_for(count), fmt::format("{}: grid 'density' ends at byte {}, past the end of the file ({} bytes; "
                                            "truncated)",
                                            part.path(), size, count));
  EXPECT_EQ(error_for(8), part.path() + ": the file ends inside the header (8 bytes; truncated or not a VDB file)");
  EXPECT_EQ(error_for(70), part.path() + ": the file ends inside a grid descriptor (70 bytes; truncated or not a VDB "
                                         "file)");
  EXPECT_EQ(error_for(4), part.path() + ": not a VDB file (no OpenVDB magic number)");
  EXPECT_EQ(load_medium_vdb(VdbField{whole.path()}).volume->size, glm::ivec3(40));
}

// The first 5000 bytes of a VDB file named by a scene: one line and exit status 1 (it was "internal error:
// std::bad_alloc", exit status 2, after OpenVDB allocated what the damaged header declared).
TEST(MediumVdb, ATruncatedFileInASceneIsOneLineFromTheCli) {
  test::TempFile whole(".vdb"), part(".part.vdb"), scene(".json"), out(".exr");
  write_grids(whole.path(), {float_grid("density", {0, 0, 0}, {39, 39, 39}, ramp)});
  write_prefix(whole.path(), part.path(), 5000);
  std::ofstream(scene.path()) << json{{"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
                                      {"objects", json::array({json{{"shape", "sphere"},
                                                                    {"material", json{{"preset", "Marble"},
                                                                                      {"field", json{{"type", "vdb"},
                                                                                                     {"file", part.path()}}}}}}})}}
                                     .dump();
  const test::CliResult result = test::run_cli("reference " + scene.path() + " -q -o " + out.path(), "timeout 60");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.output, fmt::format("lucent: {}: grid 'density' ends at byte {}, past the end of the file (5000 "
                                       "bytes; truncated)\n",
                                       part.path(), test::read_text(whole.path()).size()));
}

TEST(MediumVdb, OpenVdbsMessagesAreQuotedAsPrintableText) {
  test::TempFile file(".vdb");
  write_grids(file.path(), {float_grid("density", {0, 0, 0}, {3, 3, 3}, ramp)});
  std::string bytes = test::read_text(file.path());
  const std::size_t map = bytes.find("UniformScaleMap");
  ASSERT_NE(map, std::string::npos);
  bytes.replace(map + 7, 3, "\n\x01\xff");  // the transform's type name, which OpenVDB quotes in its message
  std::ofstream(file.path(), std::ios::binary) << bytes;
  EXPECT_EQ(test::error_message([&] { load_medium_vdb(VdbField{file.path()}); }),
            file.path() + ": cannot read the VDB file (KeyError: Map Uniform\\x0a\\x01\\xffleMap is not registered)");
}

TEST(MediumVdb, TheReaderRunsUnderAMemoryLimit) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "no address-space limit under AddressSanitizer";
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  GTEST_SKIP() << "no address-space limit under AddressSanitizer";
#endif
#endif
  test::TempFile file(".vdb");
  openvdb::FloatGrid::Ptr tiles = openvdb::FloatGrid::create(0.0f);  // active tiles: a few KiB in this process
  tiles->setName("density");
  tiles->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(255)), 1.0f, true);
  write_grids(file.path(), {tiles});
  ImportLimits& limits = vdb_read_limits();
  const ImportLimits saved = limits;
  limits.memory_bytes = std::uint64_t{16} << 20;  // less than the 64 MiB of the dense 256^3 volume
  const std::string message = test::error_message([&] { load_medium_vdb(VdbField{file.path()}); });
  limits = saved;
  EXPECT_EQ(message, file.path() + ": cannot read the VDB file: the OpenVDB reader ran out of memory (limit 16 MiB)");
  EXPECT_EQ(load_medium_vdb(VdbField{file.path()}).volume->size, glm::ivec3(256));
}

json scene_with_field(const json& field) {
  return json{{"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
              {"objects", json::array({json{{"shape", "sphere"},
                                            {"material", json{{"preset", "Marble"}, {"field", field}}}}})}};
}

TEST(MediumVdb, SceneFieldParsesAndWritesBack) {
  test::TempFile file(".vdb");
  auto transform = openvdb::math::Transform::createLinearTransform(0.5);
  write_grids(file.path(), {float_grid("density", {0, 0, 0}, {1, 1, 1}, ramp, transform)});
  const json field = {{"type", "vdb"}, {"file", file.path()}, {"density_scale", 0.5}, {"transform", "vdb-world"}};
  const Scene scene = parse_scene(scene_with_field(field).dump(), "test.json", ".");
  const MediumField& f = scene.objects[0].material->field;
  EXPECT_EQ(f.type, MediumFieldType::Volume);
  ASSERT_TRUE(f.volume && f.has_bounds);
  EXPECT_FLOAT_EQ(f.max_multiplier(), 0.5f * ramp(1, 1, 1));
  EXPECT_NEAR(f.bounds_lower.x, -0.75f, 1e-6f);  // index -1.5 at 0.5 per voxel
  EXPECT_NEAR(f.bounds_upper.z, 1.25f, 1e-6f);
  const json written = scene_to_json(scene)["objects"][0]["material"]["field"];
  EXPECT_EQ(written, (json{{"type", "vdb"}, {"file", file.path()}, {"grid", "density"}, {"density_scale", 0.5},
                           {"transform", "vdb-world"}}));
  auto scene_error = [](const json& j) {
    return test::error_message([&] { parse_scene(scene_with_field(j).dump(), "test.json", "."); });
  };
  EXPECT_EQ(scene_error({{"type", "vdb"}}),
            "test.json: /objects/0/material/field/file: a vdb field needs the file of its OpenVDB grid");
  EXPECT_EQ(scene_error({{"type", "volume"}, {"file", file.path()}, {"grid", "density"}}),
            "test.json: /objects/0/material/field/grid: only for type vdb (type is volume)");
  EXPECT_EQ(scene_error({{"type", "vdb"}, {"file", file.path()}, {"transform", "index"}}),
            "test.json: /objects/0/material/field/transform: 'index' is not one of {object-bounds|vdb-world}");
  EXPECT_EQ(scene_error({{"type", "vdb"}, {"file", "missing.vdb"}}), "./missing.vdb: cannot open the VDB file");
}

// volpath through a vdb field of constant m = 0.5 (value 1 times density_scale 0.5) against the homogeneous
// material with half the coefficients (the same medium): equal within 3 standard errors. A slab 2 mm thick (optical
// depth 2; 4 if the factor were lost, which raises the reflectance by 0.026, 8 standard errors), 300 mm wide, viewed
// cosine-weighted from above (as tests/cpu/test_references.cpp).
TEST(MediumVdb, VolpathThroughAConstantVdbMatchesTheHomogeneousMedium) {
  test::TempFile file(".vdb");
  write_grids(file.path(), {float_grid("density", {0, 0, 0}, {3, 3, 3}, [](int, int, int) { return 1.0f; })});
  auto slab = [](const std::string& material) {
    return parse_scene(R"({ "scale_mm": 1, "lights": [{ "direction": [0.5, -0.8660254, 0], "radiance": [1, 1, 1] }],
      "objects": [{ "shape": "box", "size": [300, 2, 300], "translate": [0, -1, 0], "material": )" + material + "}] }",
                       "slab", ".");
  };
  const Scene vdb = slab(R"({ "sigma_a": [0.2, 0.2, 0.2], "sigma_s": [1.8, 1.8, 1.8], "g": 0, "eta": 1.3,
      "field": { "type": "vdb", "file": ")" + file.path() + R"(", "density_scale": 0.5 } })");
  const Scene homogeneous = slab(R"({ "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [0.9, 0.9, 0.9], "g": 0, "eta": 1.3 })");
  auto reflectance = [](const Scene& scene) {
    reference::EmbreeScene rt(scene);
    reference::ReferenceScene rs{scene, rt};
    const double cos_light = -scene.lights[0].direction.y;
    reference::Accumulator acc;
    for (int i = 0; i < 20000; ++i) {
      reference::Rng rng(17, static_cast<std::uint64_t>(i));
      const double r = std::sqrt(rng.uniform()), phi = 2.0 * M_PI * rng.uniform();
      const glm::dvec3 w_o(r * std::cos(phi), std::sqrt(std::max(0.0, 1.0 - r * r)), r * std::sin(phi));
      const glm::dvec3 target(rng.uniform() - 0.5, 0.0, rng.uniform() - 0.5);
      acc.add(M_PI * reference::volpath_radiance(rs, target + 10.0 * w_o, -w_o, rng)[0] / cos_light);
    }
    return acc.estimate();
  };
  const reference::Estimate a = reflectance(vdb), b = reflectance(homogeneous);
  EXPECT_NEAR(a.mean, b.mean, 3.0 * std::hypot(a.standard_error, b.standard_error))
      << a.mean << " +- " << a.standard_error << " vs homogeneous " << b.mean << " +- " << b.standard_error;
  EXPECT_LT(a.standard_error, 0.01);
  RecordProperty("reflectance_vdb", std::to_string(a.mean) + " +- " + std::to_string(a.standard_error));
  RecordProperty("reflectance_homogeneous", std::to_string(b.mean) + " +- " + std::to_string(b.standard_error));
}

}  // namespace
}  // namespace lucent
