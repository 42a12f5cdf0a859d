// test_meshes.cpp: procedural shapes against closed-form areas and outward orientation, watertightness,
// mesh loading through assimp (files on disk, written ones, missing and garbage ones) and validate_mesh.
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <string>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include "lucent/error.h"
#include "geometry/sheet_solid.h"
#include "lucent/mesh.h"
#include "../mesh_topology.h"

namespace {

using lucent::TriangleMesh;
using lucent::test::triangle_count;

constexpr float kPi = glm::pi<float>();

glm::vec3 corner(const TriangleMesh& m, std::size_t t, std::size_t k) {
  return m.positions[m.indices[3 * t + k]];
}

// Geometric normal of triangle t by the counter-clockwise rule (not normalized).
glm::vec3 geometric_normal(const TriangleMesh& m, std::size_t t) {
  return glm::cross(corner(m, t, 1) - corner(m, t, 0), corner(m, t, 2) - corner(m, t, 0));
}

glm::vec3 centroid(const TriangleMesh& m, std::size_t t) {
  return (corner(m, t, 0) + corner(m, t, 1) + corner(m, t, 2)) / 3.0f;
}

float relative_error(float value, float exact) { return std::abs(value - exact) / exact; }

// The counter-clockwise normal of every triangle must agree with the normal stored at each of its corners
// and with the true outward direction of the shape at the triangle's centroid.
void expect_outward(const TriangleMesh& m, const std::function<glm::vec3(glm::vec3)>& outward) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (std::size_t t = 0; t < triangle_count(m); ++t) {
    glm::vec3 g = geometric_normal(m, t);
    for (std::size_t k = 0; k < 3; ++k)
      ASSERT_GT(glm::dot(g, m.normals[m.indices[3 * t + k]]), 0.0f) << "triangle " << t << " corner " << k;
    ASSERT_GT(glm::dot(g, outward(centroid(m, t))), 0.0f) << "triangle " << t;
  }
}

void expect_unit_normals(const TriangleMesh& m) {
  for (std::size_t i = 0; i < m.normals.size(); ++i) {
    glm::vec3 n = m.normals[i];
    ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z)) << "normal " << i;
    ASSERT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-4f) << "normal " << i;
  }
}

// Welds vertices with identical positions, then requires every undirected edge to be used by exactly two
// triangles, once in each direction (closed and consistently oriented).
void expect_watertight(const TriangleMesh& m) {
  std::map<std::array<float, 3>, std::uint32_t> weld;
  std::vector<std::uint32_t> id(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    std::array<float, 3> key{m.positions[i].x, m.positions[i].y, m.positions[i].z};
    id[i] = weld.emplace(key, static_cast<std::uint32_t>(weld.size())).first->second;
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t t = 0; t < triangle_count(m); ++t)
    for (std::size_t k = 0; k < 3; ++k)
      ++directed[{id[m.indices[3 * t + k]], id[m.indices[3 * t + (k + 1) % 3]]}];
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " repeated in one direction";
    ASSERT_EQ(directed.count({edge.second, edge.first}), 1u)
        << "edge " << edge.first << "-" << edge.second << " is a border (used by one triangle)";
  }
}

// ---- procedural shapes ---------------------------------------------------------------------------------

// An inscribed UV sphere's area rises towards 4 pi r^2 as the grid is refined; within 0.5% at 64 x 128.
TEST(ProceduralShapes, SphereAreaConvergesTo4PiR2) {
  const float r = 1.7f, exact = 4.0f * kPi * r * r;
  float previous_error = 1.0f;
  for (int n : {8, 16, 32, 64}) {
    float area = lucent::surface_area(lucent::make_sphere(r, n, 2 * n));
    EXPECT_LT(area, exact) << n << " rings";  // inscribed polyhedron
    float error = relative_error(area, exact);
    EXPECT_LT(error, previous_error) << n << " rings";
    previous_error = error;
  }
  EXPECT_LT(previous_error, 0.005f);
}

// Torus area 4 pi^2 R r (Pappus); within 0.5% at 128 x 64.
TEST(ProceduralShapes, TorusAreaConvergesTo4Pi2Rr) {
  const float major = 2.0f, minor = 0.5f, exact = 4.0f * kPi * kPi * major * minor;
  float previous_error = 1.0f;
  for (int n : {8, 16, 32, 64}) {
    float error = relative_error(lucent::surface_area(lucent::make_torus(major, minor, 2 * n, n)), exact);
    EXPECT_LT(error, previous_error) << n << " segments";
    previous_error = error;
  }
  EXPECT_LT(previous_error, 0.005f);
}

// Signed volume by the divergence theorem: positive when triangles wind counter-clockwise seen from outside.
double signed_volume(const TriangleMesh& m) {
  double v = 0.0;
  for (std::size_t t = 0; t < triangle_count(m); ++t) {
    glm::dvec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
               c = m.positions[m.indices[3 * t + 2]];
    v += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return v;
}

// Lathes: a closed cylinder (profile given counter-clockwise: the orientation is fixed automatically), a candle
// with a hollow, a lamp shade (a thick open cone: no point on the axis) and a hollow sphere are watertight, wind
// outward, and have their closed-form volumes within the polygonal approximation's error.
TEST(ProceduralShapes, LathesAreWatertightWithOutwardWinding) {
  const std::vector<glm::vec2> cylinder = {{0, 0}, {1, 0}, {1, 2}, {0, 2}};
  const std::vector<glm::vec2> candle = {{0, 0}, {2.5f, 0}, {2.5f, 6}, {1.6f, 6}, {1.6f, 2.5f}, {0, 2.5f}};
  const std::vector<glm::vec2> shade = {{6, 10}, {6.15f, 10}, {3.65f, 15}, {3.5f, 15}};
  struct Case {
    TriangleMesh mesh;
    double volume;
  } cases[] = {
      {lucent::make_lathe(cylinder, 256), kPi * 2.0},
      {lucent::make_lathe(candle, 256), kPi * (2.5 * 2.5 * 6.0 - 1.6 * 1.6 * 3.5)},
      {lucent::make_lathe(shade, 256), 0.0},  // Pappus below
      {lucent::make_shell(1.0f, 0.85f, 256), 4.0 / 3.0 * kPi * (1.0 - 0.85 * 0.85 * 0.85)},
  };
  // Pappus: the profile's area times the distance its centroid travels, 2 pi times the area's first moment about
  // the axis (the shoelace sum of (x_a + x_b) cross / 6).
  double first_moment_r = 0.0;
  for (std::size_t i = 0; i < shade.size(); ++i) {
    glm::dvec2 a = shade[i], b = shade[(i + 1) % shade.size()];
    double cross = a.x * b.y - b.x * a.y;
    first_moment_r += (a.x + b.x) * cross / 6.0;
  }
  cases[2].volume = 2.0 * kPi * std::abs(first_moment_r);
  for (const Case& c : cases) {
    expect_watertight(c.mesh);
    EXPECT_NO_THROW(lucent::validate_mesh(c.mesh, "lathe"));
    EXPECT_GT(signed_volume(c.mesh), 0.0);
    EXPECT_NEAR(signed_volume(c.mesh) / c.volume, 1.0, 0.002);  // 256 segments: cos(pi/256) polygon factor
  }
}

TEST(ProceduralShapes, BoxAreaIsExact) {
  TriangleMesh box = lucent::make_box({1.0f, 2.0f, 3.0f});
  EXPECT_EQ(box.positions.size(), 24u);
  EXPECT_EQ(triangle_count(box), 12u);
  EXPECT_NEAR(lucent::surface_area(box), 2.0f * (1.0f * 2.0f + 2.0f * 3.0f + 3.0f * 1.0f), 1e-5f);
}

TEST(ProceduralShapes, PlaneAreaIsExact) {
  TriangleMesh plane = lucent::make_plane({2.0f, 3.0f});
  EXPECT_EQ(plane.positions.size(), 4u);
  EXPECT_EQ(triangle_count(plane), 2u);
  EXPECT_NEAR(lucent::surface_area(plane), 6.0f, 1e-6f);
  for (glm::vec3 p : plane.positions) EXPECT_EQ(p.y, 0.0f);
  for (glm::vec3 p : plane.positions) EXPECT_NEAR(std::abs(p.x), 1.0f, 1e-6f);
  for (glm::vec3 p : plane.positions) EXPECT_NEAR(std::abs(p.z), 1.5f, 1e-6f);
}

TEST(ProceduralShapes, SphereFacesOutward) {
  TriangleMesh sphere = lucent::make_sphere(2.0f, 12, 24);
  expect_unit_normals(sphere);
  expect_outward(sphere, [](glm::vec3 p) { return p; });
  for (glm::vec3 p : sphere.positions) EXPECT_NEAR(glm::length(p), 2.0f, 1e-5f);
}

TEST(ProceduralShapes, TorusFacesOutward) {
  const float major = 2.0f, minor = 0.5f;
  TriangleMesh torus = lucent::make_torus(major, minor, 24, 12);
  expect_unit_normals(torus);
  // Outward = away from the nearest point of the tube's centre circle.
  expect_outward(torus, [&](glm::vec3 p) { return p - major * glm::normalize(glm::vec3(p.x, 0.0f, p.z)); });
  for (glm::vec3 p : torus.positions) {
    glm::vec3 core = major * glm::normalize(glm::vec3(p.x, 0.0f, p.z));
    EXPECT_NEAR(glm::length(p - core), minor, 1e-5f);
  }
}

TEST(ProceduralShapes, BoxFacesOutwardWithFlatNormals) {
  TriangleMesh box = lucent::make_box({1.0f, 2.0f, 3.0f});
  expect_unit_normals(box);
  expect_outward(box, [](glm::vec3 p) { return p; });  // convex and centred at the origin
  for (std::size_t t = 0; t < triangle_count(box); ++t) {
    glm::vec3 g = glm::normalize(geometric_normal(box, t));
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_NEAR(glm::dot(g, box.normals[box.indices[3 * t + k]]), 1.0f, 1e-6f) << "triangle " << t;
  }
}

TEST(ProceduralShapes, PlaneFacesUp) {
  TriangleMesh plane = lucent::make_plane({2.0f, 3.0f});
  expect_unit_normals(plane);
  expect_outward(plane, [](glm::vec3) { return glm::vec3(0.0f, 1.0f, 0.0f); });
}

TEST(ProceduralShapes, ClosedShapesAreWatertight) {
  expect_watertight(lucent::make_sphere(1.0f, 16, 32));
  expect_watertight(lucent::make_sphere(1.0f, 2, 3));  // smallest sphere: two fans
  expect_watertight(lucent::make_torus(2.0f, 0.5f, 24, 12));
  expect_watertight(lucent::make_box({1.0f, 2.0f, 3.0f}));
}

TEST(ProceduralShapes, PassValidation) {
  EXPECT_NO_THROW(lucent::validate_mesh(lucent::make_sphere(1.0f, 16, 32), "sphere"));
  EXPECT_NO_THROW(lucent::validate_mesh(lucent::make_torus(2.0f, 0.5f, 24, 12), "torus"));
  EXPECT_NO_THROW(lucent::validate_mesh(lucent::make_box({1.0f, 2.0f, 3.0f}), "box"));
  EXPECT_NO_THROW(lucent::validate_mesh(lucent::make_plane({2.0f, 3.0f}), "plane"));
}

// ---- validate_mesh -----------------------------------------------------------------------------------

std::string validation_message(const TriangleMesh& m) {
  try {
    lucent::validate_mesh(m, "m");
  } catch (const lucent::Error& e) {
    return e.what();
  }
  return "(no error)";
}

TriangleMesh unit_triangle() {
  TriangleMesh m;
  m.positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  m.normals.assign(3, glm::vec3(0.0f, 0.0f, 1.0f));
  m.indices = {0, 1, 2};
  return m;
}

TEST(ValidateMesh, AcceptsAGoodTriangle) { EXPECT_EQ(validation_message(unit_triangle()), "(no error)"); }

TEST(ValidateMesh, RejectsAnEmptyMesh) {
  EXPECT_EQ(validation_message(TriangleMesh{}), "m: mesh has no triangles");
}

TEST(ValidateMesh, RejectsAnIndexOutOfRange) {
  TriangleMesh m = unit_triangle();
  m.indices[2] = 7;
  EXPECT_EQ(validation_message(m), "m: index 7 out of range (3 vertices)");
}

TEST(ValidateMesh, RejectsANonFiniteCoordinate) {
  TriangleMesh m = unit_triangle();
  m.positions[1].y = std::nanf("");
  EXPECT_EQ(validation_message(m), "m: vertex 1 has a non-finite coordinate");
  m.positions[1].y = INFINITY;
  EXPECT_EQ(validation_message(m), "m: vertex 1 has a non-finite coordinate");
}

TEST(ValidateMesh, RejectsZeroArea) {
  TriangleMesh m = unit_triangle();
  m.positions[2] = {2.0f, 0.0f, 0.0f};  // collinear
  EXPECT_EQ(validation_message(m), "m: mesh has zero surface area (degenerate triangles)");
}

TEST(ValidateMesh, RejectsMismatchedNormals) {
  TriangleMesh m = unit_triangle();
  m.normals.pop_back();
  EXPECT_EQ(validation_message(m), "m: normals count differs from positions count");
}

// ---- load_mesh ---------------------------------------------------------------------------------------

std::string load_message(const std::string& path) {
  try {
    lucent::load_mesh(path);
  } catch (const lucent::Error& e) {
    return e.what();
  }
  return "(no error)";
}

// A fresh directory under the system temp folder, removed with its files after each test.
class LoadMesh : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string name = "lucent_test_meshes_" + std::to_string(std::random_device{}());
    dir_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& content) {
    std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << content;
    return path;
  }

  std::filesystem::path dir_;
};

TEST_F(LoadMesh, BunnyHasManyTrianglesAndUnitNormals) {
  const std::string path = "/usr/share/glmark2/models/bunny.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is missing (Debian package glmark2-data)";
  TriangleMesh bunny = lucent::load_mesh(path);
  EXPECT_GT(triangle_count(bunny), 1000u);
  expect_unit_normals(bunny);
  EXPECT_NO_THROW(lucent::validate_mesh(bunny, path));
}

TEST_F(LoadMesh, MissingFileIsNamed) {
  const std::string path = (dir_ / "missing.obj").string();
  EXPECT_EQ(load_message(path), path + ": no such file");
}

TEST_F(LoadMesh, OneTriangleObj) {
  TriangleMesh m = lucent::load_mesh(write("triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  ASSERT_EQ(triangle_count(m), 1u);
  EXPECT_NEAR(lucent::surface_area(m), 0.5f, 1e-6f);
  // Generated smooth normals of a lone triangle are its face normal, +z for this winding.
  expect_unit_normals(m);
  for (glm::vec3 n : m.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
  EXPECT_GT(geometric_normal(m, 0).z, 0.0f);
}

TEST_F(LoadMesh, ZeroNormalsInTheFileBecomeFaceNormals) {
  TriangleMesh m = lucent::load_mesh(
      write("zero_normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n"));
  ASSERT_EQ(triangle_count(m), 1u);
  expect_unit_normals(m);
  for (glm::vec3 n : m.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST_F(LoadMesh, GarbageIsRejectedWithTheFileName) {
  for (const char* name : {"garbage.obj", "garbage.ply", "garbage.stl", "garbage.bin"}) {
    const std::string path = write(name, std::string("\x7f\x01 this is not a mesh \xff\xfe\n{[(\n"));
    std::string message = load_message(path);
    bool cannot_read = message.rfind(path + ": cannot read mesh:", 0) == 0;
    bool no_triangles = message == path + ": the file holds no triangles";
    EXPECT_TRUE(cannot_read || no_triangles) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST_F(LoadMesh, PointsAndLinesAloneHoldNoTriangles) {
  const std::string path = write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\np 1\n");
  EXPECT_EQ(load_message(path), path + ": the file holds no triangles");
}

TEST_F(LoadMesh, LinesAndPointsBesideTrianglesAreDropped) {
  TriangleMesh m =
      lucent::load_mesh(write("mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nl 1 4\np 4\nf 1 2 3\n"));
  EXPECT_EQ(m.positions.size(), 3u);  // the line's and the point's vertex go with them
  EXPECT_EQ(triangle_count(m), 1u);
  EXPECT_NEAR(lucent::surface_area(m), 0.5f, 1e-6f);
  EXPECT_NO_THROW(lucent::validate_mesh(m, "mixed.obj"));
}

}  // namespace

// The same unit right triangle (area 0.5, normal +z) in each text format the scene files accept.
TEST_F(LoadMesh, StlPlyAndGltfGiveTheSameTriangle) {
  const std::string stl =
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
      "endsolid t\n";
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  // glTF 2.0 with the 36-byte position buffer embedded as base64 (floats 0,0,0, 1,0,0, 0,1,0).
  const std::string gltf = R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "scene": 0,
    "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}]})";
  for (const auto& [name, text] : {std::pair{"t.stl", stl}, std::pair{"t.ply", ply}, std::pair{"t.gltf", gltf}}) {
    SCOPED_TRACE(name);
    TriangleMesh m = lucent::load_mesh(write(name, text));
    ASSERT_EQ(triangle_count(m), 1u);
    EXPECT_NEAR(lucent::surface_area(m), 0.5f, 1e-6f);
    expect_unit_normals(m);
    EXPECT_GT(geometric_normal(m, 0).z, 0.0f);
  }
}

TEST_F(LoadMesh, ThreeDsCubeFromGlmark2) {
  const std::string path = "/usr/share/glmark2/models/cube.3ds";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is missing (Debian package glmark2-data)";
  TriangleMesh cube = lucent::load_mesh(path);
  EXPECT_EQ(triangle_count(cube), 12u);
  expect_unit_normals(cube);
}

// A closed surface made a sheet is a hollow shell: no walls, the inner surface the outer one moved inward by the
// thickness along its normals, wound the other way (every edge met twice, in opposite directions).
TEST(SheetSolid, AClosedSurfaceBecomesAHollowShell) {
  const lucent::TriangleMesh sphere = lucent::make_sphere(1.0f, 12, 24);
  const lucent::TriangleMesh shell = lucent::sheet_solid(sphere, 0.1f);
  ASSERT_EQ(shell.indices.size(), 2 * sphere.indices.size());
  for (std::size_t v = sphere.positions.size(); v < shell.positions.size(); ++v)
    EXPECT_NEAR(glm::length(shell.positions[v]), 0.9f, 0.01f) << v;  // the vertex normals of a sphere are radial
  const glm::vec3 a = shell.positions[shell.indices[sphere.indices.size()]];
  const glm::vec3 b = shell.positions[shell.indices[sphere.indices.size() + 1]];
  const glm::vec3 c = shell.positions[shell.indices[sphere.indices.size() + 2]];
  EXPECT_LT(glm::dot(glm::cross(b - a, c - a), a), 0.0f);  // inner faces face the centre
  EXPECT_THROW(lucent::sheet_solid(sphere, 0.0f), lucent::Error);
}
