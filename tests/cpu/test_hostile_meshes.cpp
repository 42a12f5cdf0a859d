// test_hostile_meshes.cpp: mesh files made to break the loader: the importer's child process turning crashes,
// runaway loops and allocations into errors, and what the importer returns validated.
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

#if defined(__SANITIZE_ADDRESS__)
#define LUCENT_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LUCENT_TEST_ASAN 1
#endif
#endif

namespace lucent {
namespace {

using test::error_message;
using test::TempFile;

const std::string kHostile = std::string(LUCENT_TEST_DATA) + "/hostile/";

void write_file(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

float max_position_difference(const TriangleMesh& a, const TriangleMesh& b) {
  float largest = 0.0f;
  for (std::size_t i = 0; i < a.positions.size(); ++i)
    largest = std::max(largest, glm::length(a.positions[i] - b.positions[i]));
  return largest;
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

TEST(HostileMesh, DegenerateTrianglesAreRefused) {
  const TempFile file(".obj");
  write_file(file.path(), "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  EXPECT_EQ(error_message([&] { load_mesh(file.path()); }),
            file.path() + ": mesh has zero surface area (degenerate triangles)");
}

}  // namespace
}  // namespace lucent
