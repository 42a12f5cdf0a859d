// test_mesh_uvs.cpp: texture coordinates along the mesh path: read from OBJ files (all meshes or none), laid out
// without overlap by the procedural shapes, carried through the importer's child process, transformed(),
// deformed_mesh() and scene_at_time(), checked by validate_mesh and written as glTF TEXCOORD_0.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "lucent/mesh.h"
#include "lucent/scene.h"
#include "lucent/scene_writer.h"
#include "scene/import_guard.h"
#include "../mesh_topology.h"
#include "../test_support.h"

namespace {

using lucent::TriangleMesh;
using lucent::test::error_message;
using lucent::test::TempFile;
using lucent::test::triangle_count;

std::array<glm::vec2, 3> uv_triangle(const TriangleMesh& m, std::size_t t) {
  return {m.uvs[m.indices[3 * t]], m.uvs[m.indices[3 * t + 1]], m.uvs[m.indices[3 * t + 2]]};
}

double cross2(glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; }

double signed_area(const std::array<glm::vec2, 3>& t) {
  return 0.5 * cross2(glm::dvec2(t[1]) - glm::dvec2(t[0]), glm::dvec2(t[2]) - glm::dvec2(t[0]));
}

// True when the interiors of two triangles overlap by more than `eps` (separating axis test on the six edge
// normals): triangles that only share an edge or a corner do not overlap.
bool interiors_overlap(const std::array<glm::vec2, 3>& a, const std::array<glm::vec2, 3>& b, double eps) {
  for (const auto* tri : {&a, &b})
    for (int e = 0; e < 3; ++e) {
      glm::dvec2 d = glm::dvec2((*tri)[(e + 1) % 3]) - glm::dvec2((*tri)[e]);
      glm::dvec2 axis(-d.y, d.x);
      double length = std::hypot(axis.x, axis.y);
      if (length == 0.0) continue;
      axis /= length;
      double a_lo = 1e300, a_hi = -1e300, b_lo = 1e300, b_hi = -1e300;
      for (glm::vec2 p : a) a_lo = std::min(a_lo, glm::dot(axis, glm::dvec2(p))), a_hi = std::max(a_hi, glm::dot(axis, glm::dvec2(p)));
      for (glm::vec2 p : b) b_lo = std::min(b_lo, glm::dot(axis, glm::dvec2(p))), b_hi = std::max(b_hi, glm::dot(axis, glm::dvec2(p)));
      if (std::min(a_hi, b_hi) - std::max(a_lo, b_lo) <= eps) return false;  // separated (or only touching)
    }
  return true;
}

// "triangles s and t overlap" for the first pair that does, or "".
std::string first_uv_overlap(const TriangleMesh& m) {
  for (std::size_t s = 0; s < triangle_count(m); ++s)
    for (std::size_t t = s + 1; t < triangle_count(m); ++t)
      if (interiors_overlap(uv_triangle(m, s), uv_triangle(m, t), 1e-7))
        return "triangles " + std::to_string(s) + " and " + std::to_string(t) + " overlap";
  return "";
}

// One texture coordinate per position, all in [0, 1]^2; every triangle of non-zero area has non-zero area in
// texture space; no two triangles overlap there (pairwise); their areas add up to at most 1.
void expect_injective_uvs(const TriangleMesh& m) {
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  for (std::size_t i = 0; i < m.uvs.size(); ++i) {
    ASSERT_GE(m.uvs[i].x, 0.0f) << "vertex " << i;
    ASSERT_LE(m.uvs[i].x, 1.0f) << "vertex " << i;
    ASSERT_GE(m.uvs[i].y, 0.0f) << "vertex " << i;
    ASSERT_LE(m.uvs[i].y, 1.0f) << "vertex " << i;
  }
  double total = 0.0;
  for (std::size_t t = 0; t < triangle_count(m); ++t) {
    glm::vec3 p0 = m.positions[m.indices[3 * t]], p1 = m.positions[m.indices[3 * t + 1]];
    glm::vec3 p2 = m.positions[m.indices[3 * t + 2]];
    double area = std::abs(signed_area(uv_triangle(m, t)));
    if (glm::length(glm::cross(p1 - p0, p2 - p0)) > 0.0f) {
      ASSERT_GT(area, 1e-9) << "triangle " << t;
    }
    total += area;
  }
  EXPECT_LE(total, 1.0 + 1e-5);
  EXPECT_EQ(first_uv_overlap(m), "");
}

std::vector<glm::vec2> profile_of_a_cup() {
  return {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 2.0f}, {0.9f, 2.0f}, {0.9f, 0.1f}, {0.0f, 0.1f}};
}

// ---- the test of the test ------------------------------------------------------------------------------------

TEST(UvOverlap, DetectsOverlapAndAllowsSharedEdges) {
  std::array<glm::vec2, 3> a{glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1)};
  std::array<glm::vec2, 3> shares_edge{glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)};
  std::array<glm::vec2, 3> inside{glm::vec2(0.1f, 0.1f), glm::vec2(0.2f, 0.1f), glm::vec2(0.1f, 0.2f)};
  EXPECT_FALSE(interiors_overlap(a, shares_edge, 1e-7));
  EXPECT_TRUE(interiors_overlap(a, inside, 1e-7));
  TriangleMesh folded = lucent::make_plane({1.0f, 1.0f});
  EXPECT_EQ(first_uv_overlap(folded), "");
  folded.uvs[3] = {0.9f, 0.1f};  // the second triangle folds onto the first
  EXPECT_EQ(first_uv_overlap(folded), "triangles 0 and 1 overlap");
}

// ---- procedural shapes ---------------------------------------------------------------------------------------

TEST(ProceduralUvs, SphereIsInjective) {
  expect_injective_uvs(lucent::make_sphere(1.0f, 6, 12));
  expect_injective_uvs(lucent::make_sphere(1.0f, 2, 3));
}

TEST(ProceduralUvs, TorusIsInjective) { expect_injective_uvs(lucent::make_torus(1.0f, 0.3f, 12, 6)); }

TEST(ProceduralUvs, BoxAndPlaneAreInjective) {
  expect_injective_uvs(lucent::make_box({1.0f, 2.0f, 3.0f}));
  expect_injective_uvs(lucent::make_plane({2.0f, 3.0f}));
}

TEST(ProceduralUvs, LatheAndShellAreInjective) {
  std::vector<glm::vec2> cup = profile_of_a_cup();
  expect_injective_uvs(lucent::make_lathe(cup, 10));
  expect_injective_uvs(lucent::make_shell(1.0f, 0.8f, 10));
}

// Seam copies repeat the position and the normal bit for bit: the surface renders as with one shared vertex.
// (Sphere and torus have no creases: vertices at one position are all copies of one.)
TEST(ProceduralUvs, SeamCopiesRepeatPositionAndNormal) {
  for (const TriangleMesh& m : {lucent::make_sphere(1.0f, 8, 16), lucent::make_torus(1.0f, 0.3f, 8, 6)}) {
    std::map<std::array<float, 3>, glm::vec3> normal_at;
    std::size_t copies = 0;
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      glm::vec3 p = m.positions[i];
      auto [it, inserted] = normal_at.emplace(std::array<float, 3>{p.x, p.y, p.z}, m.normals[i]);
      if (inserted) continue;
      ++copies;
      ASSERT_EQ(it->second, m.normals[i]) << "vertex " << i;
    }
    EXPECT_GT(copies, 0u);
  }
}

// ---- copies of meshes ----------------------------------------------------------------------------------------

TEST(MeshUvs, TransformedKeepsThem) {
  TriangleMesh sphere = lucent::make_sphere(1.0f, 4, 8);
  glm::mat4 m = glm::scale(glm::translate(glm::mat4(1.0f), {1.0f, 2.0f, 3.0f}), glm::vec3(2.0f));
  EXPECT_EQ(lucent::transformed(sphere, m).uvs, sphere.uvs);
  TriangleMesh bare = sphere;
  bare.uvs.clear();
  EXPECT_TRUE(lucent::transformed(bare, m).uvs.empty());
}

TEST(MeshUvs, DeformedKeepsTheRestPoseUvs) {
  TriangleMesh lathe = lucent::make_lathe(profile_of_a_cup(), 12);
  lucent::Deformation bend;
  bend.type = lucent::DeformationType::Bend;
  bend.amplitude = 0.5f;
  bend.period_s = 2.0f;
  TriangleMesh bent = lucent::deformed_mesh(lathe, bend, 0.5);
  EXPECT_NE(bent.positions, lathe.positions);
  EXPECT_EQ(bent.uvs, lathe.uvs);
}

// The copies of a vertex along a seam get the same deformed normal, as one shared vertex would.
TEST(MeshUvs, DeformedSeamCopiesShareTheirNormal) {
  TriangleMesh sphere = lucent::make_sphere(1.0f, 8, 16);
  lucent::Deformation wave;
  wave.type = lucent::DeformationType::Wave;
  wave.amplitude = 0.3f;
  wave.period_s = 1.0f;
  TriangleMesh waved = lucent::deformed_mesh(sphere, wave, 0.3);
  std::map<std::array<float, 3>, glm::vec3> normal_at;
  for (std::size_t i = 0; i < sphere.positions.size(); ++i) {
    glm::vec3 p = sphere.positions[i];
    auto [it, inserted] = normal_at.emplace(std::array<float, 3>{p.x, p.y, p.z}, waved.normals[i]);
    if (!inserted) {
      ASSERT_EQ(it->second, waved.normals[i]) << "vertex " << i;
    }
  }
}

TEST(MeshUvs, SceneAtTimeKeepsThem) {
  lucent::Scene scene;
  lucent::SceneObject object;
  object.mesh = lucent::make_torus(1.0f, 0.3f, 8, 6);
  object.deformation.type = lucent::DeformationType::Melt;
  object.deformation.amplitude = 0.3f;
  scene.objects.push_back(object);
  lucent::Scene frozen = lucent::scene_at_time(scene, 0.4);
  EXPECT_EQ(frozen.objects[0].mesh.uvs, object.mesh.uvs);
}

// ---- validate_mesh -------------------------------------------------------------------------------------------

TEST(MeshUvs, ValidateMeshChecksThem) {
  TriangleMesh m = lucent::make_plane({1.0f, 1.0f});
  EXPECT_EQ(error_message([&] { lucent::validate_mesh(m, "plane"); }), "");
  m.uvs.pop_back();
  EXPECT_EQ(error_message([&] { lucent::validate_mesh(m, "plane"); }),
            "plane: texture coordinate count 3 differs from vertex count 4");
  m.uvs.clear();
  EXPECT_EQ(error_message([&] { lucent::validate_mesh(m, "plane"); }), "");
  m = lucent::make_plane({1.0f, 1.0f});
  m.uvs[2].y = std::nanf("");
  EXPECT_EQ(error_message([&] { lucent::validate_mesh(m, "plane"); }),
            "plane: vertex 2 has a non-finite texture coordinate");
  m.uvs[2].y = -INFINITY;
  EXPECT_EQ(error_message([&] { lucent::validate_mesh(m, "plane"); }),
            "plane: vertex 2 has a non-finite texture coordinate");
}

// ---- loading -------------------------------------------------------------------------------------------------

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

TEST(MeshUvs, ObjWithUvsLoadsThem) {
  TempFile obj(".obj");
  write_text(obj.path(), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25 0.5\nvt 0.75 0.5\nvt 0.25 1.5\nf 1/1 2/2 3/3\n");
  TriangleMesh m = lucent::load_mesh(obj.path());
  ASSERT_EQ(triangle_count(m), 1u);
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  std::map<float, glm::vec2> uv_at_x;  // corners are told apart by position
  for (std::size_t i = 0; i < m.positions.size(); ++i) uv_at_x[m.positions[i].x + 2.0f * m.positions[i].y] = m.uvs[i];
  EXPECT_EQ(uv_at_x.at(0.0f), glm::vec2(0.25f, 0.5f));
  EXPECT_EQ(uv_at_x.at(1.0f), glm::vec2(0.75f, 0.5f));
  EXPECT_EQ(uv_at_x.at(2.0f), glm::vec2(0.25f, 1.5f));  // read as written, outside [0, 1] too
}

TEST(MeshUvs, ObjWithoutUvsHasNone) {
  TempFile obj(".obj");
  write_text(obj.path(), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(lucent::load_mesh(obj.path()).uvs.empty());
}

TEST(MeshUvs, ObjWithUvsInOnlySomeMeshesDropsThemWithAWarning) {
  TempFile obj(".obj");
  write_text(obj.path(),
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
             "o textured\nf 1/1 2/2 3/3\no bare\nf 4 5 6\n");
  ::testing::internal::CaptureStderr();
  TriangleMesh m = lucent::load_mesh(obj.path());
  std::string warnings = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(triangle_count(m), 2u);
  EXPECT_TRUE(m.uvs.empty());
  EXPECT_EQ(warnings,
            "lucent: warning: " + obj.path() + ": texture coordinates dropped: only 1 of 2 meshes have them\n");
}

TEST(MeshUvs, ImporterChildProcessCarriesThem) {
  TriangleMesh sphere = lucent::make_sphere(1.0f, 5, 7);
  TriangleMesh back = lucent::import_in_child("sphere", [&] { return sphere; }, lucent::ImportLimits{});
  EXPECT_EQ(back.positions, sphere.positions);
  EXPECT_EQ(back.normals, sphere.normals);
  EXPECT_EQ(back.indices, sphere.indices);
  EXPECT_EQ(back.uvs, sphere.uvs);
  sphere.uvs.clear();
  EXPECT_TRUE(lucent::import_in_child("sphere", [&] { return sphere; }, lucent::ImportLimits{}).uvs.empty());
  sphere.uvs.resize(3);  // neither none nor one per vertex: the child refuses to send it
  EXPECT_EQ(error_message([&] { lucent::import_in_child("sphere", [&] { return sphere; }, lucent::ImportLimits{}); }),
            "sphere: cannot read mesh: the importer returned " + std::to_string(sphere.positions.size()) +
                " normals and 3 texture coordinates for " + std::to_string(sphere.positions.size()) + " vertices");
}

// ---- glTF ----------------------------------------------------------------------------------------------------

TEST(MeshUvs, GltfRoundTripKeepsThem) {
  TempFile gltf(".gltf");
  TriangleMesh torus = lucent::make_torus(1.0f, 0.4f, 6, 5);
  lucent::write_gltf(gltf.path(), torus);
  TriangleMesh back = lucent::load_mesh(gltf.path());
  ASSERT_EQ(triangle_count(back), triangle_count(torus));
  ASSERT_EQ(back.uvs.size(), back.positions.size());
  for (std::size_t c = 0; c < torus.indices.size(); ++c) {  // corner by corner: assimp may reorder vertices
    glm::vec2 expected = torus.uvs[torus.indices[c]], actual = back.uvs[back.indices[c]];
    ASSERT_EQ(back.positions[back.indices[c]], torus.positions[torus.indices[c]]) << "corner " << c;
    ASSERT_NEAR(actual.x, expected.x, 1e-6f) << "corner " << c;
    ASSERT_NEAR(actual.y, expected.y, 1e-6f) << "corner " << c;
  }
  torus.uvs.clear();
  lucent::write_gltf(gltf.path(), torus);
  EXPECT_TRUE(lucent::load_mesh(gltf.path()).uvs.empty());
}

}  // namespace
