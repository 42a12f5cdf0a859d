// test_viewer_session.cpp: the viewer's scene loading (apps/lucent/viewer/viewer_session.h) keeps every exception a
// load throws for display, not only lucent::Error: a scene whose volume file needs more memory than the process may
// have (std::bad_alloc) leaves the session with the message instead of ending the viewer.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include <sys/resource.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "viewer/viewer_session.h"
#include "../test_support.h"

namespace lucent {
namespace {

// The address space the process has now [bytes] (/proc/self/statm, in pages).
std::uint64_t address_space_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  statm >> pages;
  return pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

TEST(ViewerSession, ALoadThatRunsOutOfMemoryIsKeptAsTheError) {
#if defined(LUCENT_TEST_ASAN)
  GTEST_SKIP() << "no address-space limit under AddressSanitizer";
#endif
  test::TempFile scene(".json"), header(".volume.json"), raw(".raw");
  // 512 x 256 x 256 uint8 voxels: a valid 32 MiB volume file, read into memory when the scene loads.
  {
    std::ofstream data(raw.path(), std::ios::binary);
    const std::string slice(512 * 256, '\x10');
    for (int z = 0; z < 256; ++z) data << slice;
  }
  std::ofstream(header.path()) << R"({"size": [512, 256, 256], "format": "uint8", "data": ")"
                               << std::filesystem::path(raw.path()).filename().string() << "\"}\n";
  std::ofstream(scene.path()) << R"({"lights": [{"direction": [0, -1, 0]}], "objects": [{"shape": "sphere",
    "material": {"preset": "Marble", "field": {"type": "volume", "file": ")"
                              << header.path() << "\"}}}]}\n";
  viewer::ViewerSession session(scene.path(), {});
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_AS, &saved), 0);
  const rlim_t limited = address_space_bytes() + (std::uint64_t{16} << 20);  // less than the volume's 32 MiB
  const rlimit limit{limited, saved.rlim_max};
  ASSERT_EQ(setrlimit(RLIMIT_AS, &limit), 0);
  bool loaded = true;
  try {
    loaded = session.load();
  } catch (...) {
    setrlimit(RLIMIT_AS, &saved);
    FAIL() << "the load threw instead of keeping the error";
  }
  setrlimit(RLIMIT_AS, &saved);
  EXPECT_FALSE(loaded);
  EXPECT_EQ(session.error(), scene.path() + ": cannot load the scene: std::bad_alloc");
  EXPECT_EQ(session.renderer(), nullptr);
}

}  // namespace
}  // namespace lucent
