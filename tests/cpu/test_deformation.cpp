// test_deformation.cpp: per-frame deformations (bend, melt, wave) and scenes frozen at a time.
#include <cmath>

#include <gtest/gtest.h>

#include "../test_support.h"
#include "lucent/error.h"
#include "lucent/scene.h"

namespace {

using namespace lucent;

TriangleMesh column() {
  // Rings at every unit of height, so that displacements growing with height^2 differ from linear ones.
  const std::vector<glm::vec2> profile = {{0, 0}, {1, 0}, {1, 1}, {1, 2}, {1, 3}, {1, 4}, {0, 4}};
  return make_lathe(profile, 32);
}

double signed_volume(const TriangleMesh& m) {
  double v = 0.0;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3)
    v += glm::dot(glm::dvec3(m.positions[m.indices[t]]),
                  glm::cross(glm::dvec3(m.positions[m.indices[t + 1]]), glm::dvec3(m.positions[m.indices[t + 2]]))) / 6.0;
  return v;
}

TEST(Deformation, BendSwaysTheTopAndKeepsTheBase) {
  TriangleMesh mesh = column();
  Deformation bend{DeformationType::Bend, 0.5f, 4.0f};
  TriangleMesh rest = deformed_mesh(mesh, bend, 0.0), quarter = deformed_mesh(mesh, bend, 1.0);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    EXPECT_NEAR(glm::length(rest.positions[i] - mesh.positions[i]), 0.0f, 1e-6f) << "sin(0) = 0: at rest";
    float h = mesh.positions[i].y / 4.0f;
    EXPECT_NEAR(quarter.positions[i].x - mesh.positions[i].x, 0.5f * h * h, 1e-5f) << "amplitude x height^2 at T/4";
    EXPECT_NEAR(glm::length(quarter.normals[i]), 1.0f, 1e-4f);
  }
}

// start_s shifts the cycle: a still image (render time 0) of a pose part-way through it, the same pose as at that time.
TEST(Deformation, StartTimeShiftsTheCycle) {
  TriangleMesh mesh = column();
  Deformation bend{DeformationType::Bend, 0.5f, 4.0f};
  Deformation shifted = bend;
  shifted.start_s = 1.0f;
  TriangleMesh at_quarter = deformed_mesh(mesh, bend, 1.0), started = deformed_mesh(mesh, shifted, 0.0);
  ASSERT_EQ(at_quarter.positions.size(), started.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    EXPECT_EQ(started.positions[i], at_quarter.positions[i]);
    float h = mesh.positions[i].y / 4.0f;
    EXPECT_NEAR(started.positions[i].x - mesh.positions[i].x, 0.5f * h * h, 1e-5f) << "bent at render time 0";
  }
}

TEST(Deformation, MeltLowersAndSpreadsThenRecovers) {
  TriangleMesh mesh = column();
  Deformation melt{DeformationType::Melt, 0.4f, 2.0f};
  TriangleMesh half = deformed_mesh(mesh, melt, 1.0), full = deformed_mesh(mesh, melt, 2.0);
  float top = -1e30f;
  for (const glm::vec3& p : half.positions) top = std::max(top, p.y);
  EXPECT_NEAR(top, 4.0f * (1.0f - 0.4f), 1e-4f);  // at half period the full amplitude is lost
  EXPECT_LT(signed_volume(half), signed_volume(mesh));
  EXPECT_GT(signed_volume(half), 0.0);  // still outward-wound
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    EXPECT_NEAR(glm::length(full.positions[i] - mesh.positions[i]), 0.0f, 1e-5f) << "periodic";
}

TEST(Deformation, SceneAtTimeFreezesBlobsIntoClosedMeshes) {
  Scene scene = parse_scene(R"({
    "objects": [{ "shape": "blobs", "segments": 24, "material": "Marble" },
                { "shape": "box", "deform": { "type": "wave", "amplitude": 0.2 }, "albedo": [0.5, 0.5, 0.5] }]
  })",
                            "blob scene", ".");
  ASSERT_EQ(scene.objects[0].blob_resolution, 24);
  EXPECT_TRUE(scene.objects[0].mesh.positions.empty());
  Scene a = scene_at_time(scene, 0.5), b = scene_at_time(scene, 2.5);
  EXPECT_FALSE(a.objects[0].animated());
  EXPECT_NO_THROW(validate_mesh(a.objects[0].mesh, "blobs at 0.5 s"));
  EXPECT_GT(signed_volume(a.objects[0].mesh), 0.0);
  EXPECT_NE(a.objects[0].mesh.positions.size(), 0u);
  EXPECT_NE(a.objects[0].mesh.positions, b.objects[0].mesh.positions);
  EXPECT_NE(a.objects[1].mesh.positions, b.objects[1].mesh.positions);
}

TEST(Deformation, BadInput) {
  auto error = [](const std::string& object) {
    return test::error_message([&] { parse_scene(R"({"objects": [)" + object + "]}", "s.json", "."); });
  };
  EXPECT_EQ(error(R"({"shape": "box", "deform": {"type": "twist"}, "albedo": [1, 1, 1]})"),
            "s.json: /objects/0/deform/type: 'twist' is not one of {bend|melt|wave}");
  EXPECT_EQ(error(R"({"shape": "box", "deform": {"type": "melt", "amplitude": 1.5}, "albedo": [1, 1, 1]})"),
            "s.json: /objects/0/deform/amplitude: 1.5 must be below 1 for melt (the fraction of height lost)");
  EXPECT_EQ(error(R"({"shape": "blobs", "translate": [1, 0, 0], "material": "Marble"})"),
            "s.json: /objects/0/translate: not supported for blobs (the field is fixed in world space)");
}

}  // namespace
