// test_hostile_meshes.cpp: mesh files made to break the loader: truncated and oversized PLY files refused
// before the importer reads them, the importer's child process turning crashes, runaway loops and allocations
// into errors, and what the importer returns validated. Files the fuzzer found are in tests/data/hostile/.
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "../cli_runner.h"
#include "../test_support.h"
#include "lucent/error.h"
#include "lucent/mesh.h"
#include "scene/import_guard.h"
#include "../test_paths.h"

namespace lucent {
namespace {

using test::error_message;
using test::TempFile;

const std::string kHostile = std::string(LUCENT_TEST_DATA) + "/hostile/";

void write_file(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

template <class T>
void append_le(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

template <class T>
void append_be(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  for (std::size_t i = sizeof(T); i-- > 0;) bytes.push_back(raw[i]);
}

std::string ply_header(const std::string& format, std::size_t vertices, std::size_t faces) {
  return "ply\nformat " + format + " 1.0\ncomment written by lucent's tests\nelement vertex " +
         std::to_string(vertices) + "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
         std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

// A binary PLY of the mesh: 12 bytes a vertex, 13 bytes a face (uchar count 3, three int indices).
std::string binary_ply(const TriangleMesh& mesh, bool big_endian = false) {
  std::string bytes = ply_header(big_endian ? "binary_big_endian" : "binary_little_endian", mesh.positions.size(),
                                 mesh.indices.size() / 3);
  const auto put = [&](auto value) { big_endian ? append_be(bytes, value) : append_le(bytes, value); };
  for (const glm::vec3& p : mesh.positions) put(p.x), put(p.y), put(p.z);
  for (std::size_t t = 0; t < mesh.indices.size() / 3; ++t) {
    bytes.push_back(3);
    for (std::size_t k = 0; k < 3; ++k) put(static_cast<std::int32_t>(mesh.indices[3 * t + k]));
  }
  return bytes;
}

float max_position_difference(const TriangleMesh& a, const TriangleMesh& b) {
  float largest = 0.0f;
  for (std::size_t i = 0; i < a.positions.size(); ++i)
    largest = std::max(largest, glm::length(a.positions[i] - b.positions[i]));
  return largest;
}

// ---- PLY size checks -------------------------------------------------------------------------------------

TEST(HostilePly, BinaryFilesLoadInBothByteOrders) {
  const TriangleMesh sphere = make_sphere(1.0f, 8, 16);
  for (bool big_endian : {false, true}) {
    const TempFile file(big_endian ? "_be.ply" : "_le.ply");
    write_file(file.path(), binary_ply(sphere, big_endian));
    const TriangleMesh loaded = load_mesh(file.path());
    EXPECT_EQ(loaded.indices.size(), sphere.indices.size());
    EXPECT_NEAR(surface_area(loaded), surface_area(sphere), 1e-4f);
  }
}

// Cut inside the face list, the file made the importer read past its buffer (a segmentation fault on a mesh
// of this size). The lists are walked before the importer runs.
TEST(HostilePly, TruncatedBinaryFileIsRefusedBeforeTheImporter) {
  const TriangleMesh sphere = make_sphere(1.0f, 64, 128);
  const std::string whole = binary_ply(sphere);
  const std::size_t faces = sphere.indices.size() / 3;
  const std::size_t face_data = whole.size() - 13 * faces;
  const TempFile file(".ply");
  write_file(file.path(), whole.substr(0, face_data + 13 * (faces * 3 / 4) + 5));  // inside face 3/4 of the way
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }),
            file.path() + ": the PLY file is truncated: face " + std::to_string(faces * 3 / 4) + " of " +
                std::to_string(faces) + " ends past the end of the file");
}

// 10^8 declared vertices in a file of a few hundred bytes took the importer tens of seconds and over a GiB
// before it gave up; the declared counts are checked against the file size first.
TEST(HostilePly, HugeDeclaredCountIsRefusedAtOnce) {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 100000000\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n";
  for (float value : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f}) append_le(bytes, value);
  bytes.push_back(3);
  for (std::int32_t index : {0, 1, 2}) append_le(bytes, index);
  const TempFile file(".ply");
  write_file(file.path(), bytes);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }),
            file.path() +
                ": the PLY header declares 100000000 vertex, 1 face elements, at least 1200000001 bytes "
                "of binary data, but the file holds 49 bytes after the header");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
}

// ASCII: at least one character and one separator a value (3 x 10^8 + 1 values).
TEST(HostilePly, HugeDeclaredCountInAsciiIsRefused) {
  const std::string text = ply_header("ascii", 100000000, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const TempFile file(".ply");
  write_file(file.path(), text);
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }),
            file.path() +
                ": the PLY header declares 100000000 vertex, 1 face elements, at least 600000001 bytes "
                "of ASCII data, but the file holds 26 bytes after the header");
}

// A count past 2^64 and the sum of counts times sizes past 2^64 do not wrap around.
TEST(HostilePly, CountsDoNotOverflow) {
  const TempFile file(".ply");
  const std::string base = file.path() + ": the PLY header declares ";
  write_file(file.path(),
             "ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551616\n"
             "property float x\nend_header\n");
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }),
            file.path() +
                ": malformed PLY header: element 'vertex' has count '18446744073709551616', not a whole "
                "number below 2^64");
  write_file(file.path(),
             "ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\n"
             "property double x\nelement face 5\nproperty int a\nend_header\n0123");
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }),
            base +
                "18446744073709551615 vertex, 5 face elements, at least 2^64 bytes of binary data, but the "
                "file holds 4 bytes after the header");
}

TEST(HostilePly, NegativeListLengthIsRefused) {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list char int vertex_indices\nend_header\n";
  for (float value : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f}) append_le(bytes, value);
  bytes.push_back(static_cast<char>(-3));
  for (std::int32_t index : {0, 1, 2}) append_le(bytes, index);
  const TempFile file(".ply");
  write_file(file.path(), bytes);
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }),
            file.path() + ": PLY face 0 of 1 has a negative list length");
}

TEST(HostilePly, MalformedHeadersAreNamed) {
  const TempFile file(".ply");
  const std::string prefix = file.path() + ": malformed PLY header: ";
  const std::pair<std::string, std::string> cases[] = {
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
       "property 'x' has unknown type 'float128'"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "'property' before any 'element'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "no 'end_header' line in the first 55 bytes"},
      {"ply\nformat ascii 1.0\nelement vertex 1e8\nend_header\n",
       "element 'vertex' has count '1e8', not a whole number below 2^64"},
      {"ply\nformat ascii 1.0\nelement face 1\nproperty list float int v\nend_header\n",
       "list count type 'float' is not an integer type"},
      {"ply\nformat binary_middle_endian 1.0\nend_header\n", "unknown format 'binary_middle_endian'"},
      {"ply\nelement vertex 0\nend_header\n", "no 'format' line"},
  };
  for (const auto& [text, problem] : cases) {
    write_file(file.path(), text);
    EXPECT_EQ(error_message([&] { load_mesh(file.path()); }), prefix + problem) << text;
  }
}

TEST(HostilePly, QuotedHeaderWordsArePrintable) {
  const TempFile file(".ply");
  write_file(file.path(), "ply\nformat ascii 1.0\nelement vertex 1\nproperty \x1b[31m\xfe x\nend_header\n");
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }),
            file.path() + ": malformed PLY header: property 'x' has unknown type '\\x1b[31m\\xfe'");
}

// The importer recognises PLY by content, whatever the extension; so does the check.
TEST(HostilePly, ContentNotExtensionDecides) {
  const TempFile file(".bin");
  write_file(file.path(), ply_header("binary_little_endian", 1000, 0));
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }),
            file.path() +
                ": the PLY header declares 1000 vertex, 0 face elements, at least 12000 bytes of binary "
                "data, but the file holds 0 bytes after the header");
}

// ---- the importer's child process ------------------------------------------------------------------------

ImportLimits quick_limits() {
  ImportLimits limits;
  limits.cpu_seconds = 1;
  limits.wall_seconds = 20;
  return limits;
}

TEST(ImportGuard, MeshComesBackExactly) {
  const TriangleMesh sphere = make_sphere(1.0f, 256, 512);  // 3 MB: many times the pipe's buffer
  const TriangleMesh copy = import_in_child(
      "sphere", [&] { return sphere; }, quick_limits());
  EXPECT_EQ(copy.positions.size(), sphere.positions.size());
  EXPECT_EQ(copy.indices, sphere.indices);
  EXPECT_EQ(max_position_difference(copy, sphere), 0.0f);
  EXPECT_EQ(copy.normals.size(), sphere.normals.size());
  EXPECT_EQ(std::memcmp(copy.normals.data(), sphere.normals.data(), sphere.normals.size() * sizeof(glm::vec3)), 0);
}

TEST(ImportGuard, ErrorsComeBackWithTheirMessage) {
  EXPECT_EQ(error_message([] {
              import_in_child(
                  "a.obj", []() -> TriangleMesh { throw Error("a.obj: cannot read mesh: bad"); }, quick_limits());
            }),
            "a.obj: cannot read mesh: bad");
  EXPECT_EQ(error_message([] {
              import_in_child(
                  "a.obj", []() -> TriangleMesh { throw std::length_error("vector"); }, quick_limits());
            }),
            "a.obj: cannot read mesh: the importer failed: vector");
}

TEST(ImportGuard, CrashBecomesAnError) {
  EXPECT_EQ(error_message([] {
              import_in_child(
                  "a.obj",
                  []() -> TriangleMesh {
                    std::raise(SIGSEGV);
                    return {};
                  },
                  quick_limits());
            }),
            "a.obj: cannot read mesh: the importer crashed (signal 11, Segmentation fault)");
  EXPECT_EQ(error_message([] {
              import_in_child(
                  "a.obj", []() -> TriangleMesh { std::abort(); }, quick_limits());
            }),
            "a.obj: cannot read mesh: the importer crashed (signal 6, Aborted)");
}

TEST(ImportGuard, EndlessLoopIsStoppedByTheCpuLimit) {
  EXPECT_EQ(error_message([] {
              import_in_child(
                  "a.obj",
                  []() -> TriangleMesh {
                    volatile std::uint64_t spins = 0;
                    for (;;) spins = spins + 1;
                  },
                  quick_limits());
            }),
            "a.obj: cannot read mesh: the importer used more than 1 s of CPU time");
}

TEST(ImportGuard, BlockedImporterIsStoppedByTheWallClock) {
  ImportLimits limits = quick_limits();
  limits.wall_seconds = 1;
  EXPECT_EQ(error_message([&] {
              import_in_child(
                  "a.obj",
                  []() -> TriangleMesh {
                    std::this_thread::sleep_for(std::chrono::seconds(30));
                    return {};
                  },
                  limits);
            }),
            "a.obj: cannot read mesh: the importer did not finish within 1 s");
}

TEST(ImportGuard, RunawayAllocationIsStoppedByTheMemoryLimit) {
#if defined(LUCENT_TEST_ASAN)
  GTEST_SKIP() << "no address-space limit under AddressSanitizer";
#endif
  ImportLimits limits = quick_limits();
  limits.memory_bytes = std::uint64_t{256} << 20;
  EXPECT_EQ(error_message([&] {
              import_in_child(
                  "a.obj",
                  []() -> TriangleMesh {
                    std::vector<char> huge(std::size_t{1} << 31, 1);
                    return {};
                  },
                  limits);
            }),
            "a.obj: cannot read mesh: the importer ran out of memory (limit 256 MiB)");
}

// ---- what the importer returns ---------------------------------------------------------------------------

TEST(HostileMesh, NonFiniteCoordinatesAreRefused) {
  const TempFile file(".obj");
  write_file(file.path(), "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n");
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }), file.path() + ": vertex 2 has a non-finite coordinate");
}

// A face index past the vertices crashes the importer (assimp 5.2.5) inside its post-processing.
TEST(HostileMesh, ImporterCrashOnAnIndexOutOfRangeIsReported) {
  const std::string path = kHostile + "ply_index_out_of_range.ply";
  EXPECT_EQ(error_message([&] { load_mesh(path); }),
            path + ": cannot read mesh: the importer crashed (signal 11, Segmentation fault)");
}

// End to end: the scene names the mesh, the command fails with one line and exit status 1.
TEST(HostileMesh, SceneWithACrashingMeshFailsCleanly) {
  const TempFile scene(".json");
  const std::string mesh = kHostile + "ply_index_out_of_range.ply";
  write_file(scene.path(), R"({"objects": [{"mesh": ")" + mesh + R"(", "material": "Marble"}]})");
  const test::CliResult result = test::run_cli("reference " + scene.path() + " --spp 1 -q -o /nonexistent-dir/x.exr");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.output, "lucent: " + scene.path() + ": /objects/0/mesh: " + mesh +
                               ": cannot read mesh: the importer crashed (signal 11, Segmentation fault)\n");
}

// A file whose meshes hold no face (an OBJ cut off before its faces) is named for what it lacks, not in the
// importer's words ("all meshes are orphaned").
TEST(HostileMesh, AFileWithoutFacesSaysSo) {
  TempFile file(".obj");
  write_file(file.path(), "v 0 0 0\nv 1 0 0\nv 0 1");
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }),
            file.path() + ": cannot read mesh: it holds no faces (no triangles to render; is the file truncated?)");
}

TEST(HostileMesh, DegenerateTrianglesAreRefused) {
  const TempFile file(".obj");
  write_file(file.path(), "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }),
            file.path() + ": mesh has zero surface area (degenerate triangles)");
}

}  // namespace
}  // namespace lucent
