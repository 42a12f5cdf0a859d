// test_input_files.cpp: every input file is a regular file. A FIFO given as a scene, mesh, map, image, volume or
// bench configuration is one line naming it (it used to block the open forever), a directory too; a precompute
// cache entry that is not a regular file is derived data: a warning, removed and recomputed.
#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>

#include <gtest/gtest.h>

#include "../cli_runner.h"
#include "../temp_cache_dir.h"
#include "cache/precompute_cache.h"
#include "io/input_file.h"
#include "lucent/error.h"
#include "lucent/image.h"

namespace {

namespace fs = std::filesystem;
using lucent::test::run_cli;

fs::path input_files_dir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / "lucent_input_files" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const lucent::Error& e) {
    return e.what();
  }
  return "(no error)";
}

// A command that would block on a FIFO is stopped after 30 s instead of hanging the test run.
constexpr const char* kNoHang = "timeout 30";

TEST(InputFiles, OnlyRegularFilesAreRead) {
  const fs::path dir = input_files_dir("library");
  write_text(dir / "a.txt", "text");
  ASSERT_EQ(::mkfifo((dir / "f.png").c_str(), 0600), 0);
  EXPECT_EQ(input_error([&] { lucent::require_regular_file((dir / "a.txt").string()); }), "(no error)");
  EXPECT_EQ(input_error([&] { lucent::require_regular_file((dir / "missing.txt").string()); }), "(no error)");
  EXPECT_EQ(input_error([&] { lucent::require_regular_file(dir.string()); }),
            dir.string() + ": is a directory, not a regular file");
  EXPECT_EQ(input_error([&] { lucent::require_regular_file("/dev/zero"); }),
            "/dev/zero: is a character device, not a regular file");
  const std::string fifo = (dir / "f.png").string();
  EXPECT_EQ(input_error([&] { lucent::read_png(fifo); }), fifo + ": is a FIFO, not a regular file");
  EXPECT_EQ(input_error([&] { lucent::read_exr(fifo); }), fifo + ": is a FIFO, not a regular file");
  EXPECT_EQ(input_error([&] { lucent::read_hdr(fifo); }), fifo + ": is a FIFO, not a regular file");
  fs::create_symlink("f.png", dir / "link.png");  // a link is followed to what it names
  EXPECT_EQ(input_error([&] { lucent::read_png((dir / "link.png").string()); }),
            (dir / "link.png").string() + ": is a FIFO, not a regular file");
}

TEST(CliInputFiles, FifoAndDirectoryInputsAreRefusedNamingThePath) {
  const fs::path dir = input_files_dir("cli");
  ASSERT_EQ(::mkfifo((dir / "fifo.obj").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((dir / "fifo.png").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((dir / "fifo.json").c_str(), 0600), 0);
  const std::string scene_start = R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]}, "lights": [{"direction": [0, 0, -1]}],
    "render": {"width": 8, "height": 6}, "objects": [)";
  write_text(dir / "mesh.json", scene_start + R"({"mesh": "fifo.obj", "material": "Skin1"}]})");
  write_text(dir / "map.json",
             scene_start + R"({"shape": "sphere", "material": {"albedo_map": "fifo.png", "mfp_mm": 1}}]})");
  write_text(dir / "volume.json",
             scene_start + R"({"shape": "sphere", "material": {"preset": "Skin1", "field": {"type": "volume", "file": "fifo.json"}}}]})");
  const std::string reference = " --integrator bssrdf --spp 1 -q -o " + (dir / "r.exr").string();
  const std::pair<std::string, std::string> cases[] = {
      {"reference " + (dir / "mesh.json").string() + reference, (dir / "fifo.obj").string()},
      {"reference " + (dir / "map.json").string() + reference, (dir / "fifo.png").string()},
      {"reference " + (dir / "volume.json").string() + reference, (dir / "fifo.json").string()},
      {"reference " + (dir / "fifo.json").string() + reference, (dir / "fifo.json").string()},
      {"tonemap " + (dir / "fifo.png").string() + " -o " + (dir / "out.png").string(), (dir / "fifo.png").string()},
      {"bench " + (dir / "fifo.json").string() + " -o " + (dir / "bench").string(), (dir / "fifo.json").string()},
  };
  for (const auto& [arguments, path] : cases) {
    auto r = run_cli(arguments, kNoHang);
    EXPECT_EQ(r.exit_code, 1) << arguments;
    EXPECT_NE(r.output.find(path + ": is a FIFO, not a regular file\n"), std::string::npos) << arguments << "\n"
                                                                                         << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
  auto scene_is_directory = run_cli("reference " + dir.string() + reference, kNoHang);
  EXPECT_EQ(scene_is_directory.exit_code, 1);
  EXPECT_EQ(scene_is_directory.output, "lucent: " + dir.string() + ": is a directory; give a scene file (JSON)\n");
  EXPECT_FALSE(fs::exists(dir / "r.exr"));
}

class InputFilesCache : public ::testing::Test {
 protected:
  lucent::test::TempCacheDir cache_dir_;
  lucent::cache::Key key_ = lucent::cache::Key("test-kind", 1).text("entry");
  std::vector<std::byte> payload_ = {std::byte{1}, std::byte{2}, std::byte{3}};

  // load() misses with one warning naming the entry, removes it, and the entry is stored and read again.
  void expect_replaced(const std::string& kind) {
    const fs::path path = lucent::cache::entry_path(key_);
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(lucent::cache::load(key_), std::nullopt);
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "lucent: warning: " + path.string() +
                                                            ": precompute cache entry is " + kind +
                                                            ", not a file; removed and recomputed\n");
    EXPECT_FALSE(fs::exists(fs::symlink_status(path)));
    lucent::cache::store(key_, payload_);
    EXPECT_EQ(lucent::cache::load(key_), payload_);
  }
};

TEST_F(InputFilesCache, DirectoryEntryIsRemovedAndRecomputed) {
  const fs::path path = lucent::cache::entry_path(key_);
  fs::create_directories(path / "inside");
  expect_replaced("a directory");
}

TEST_F(InputFilesCache, FifoEntryIsRemovedAndRecomputed) {
  const fs::path path = lucent::cache::entry_path(key_);
  fs::create_directories(path.parent_path());
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  expect_replaced("a FIFO");
}

// The store of a key that was never loaded finds the FIFO too: it is replaced, never written into.
TEST_F(InputFilesCache, StoreReplacesAFifoEntry) {
  const fs::path path = lucent::cache::entry_path(key_);
  fs::create_directories(path.parent_path());
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  ::testing::internal::CaptureStderr();
  lucent::cache::store(key_, payload_);
  ::testing::internal::GetCapturedStderr();
  EXPECT_TRUE(fs::is_regular_file(path));
  EXPECT_EQ(lucent::cache::load(key_), payload_);
}

// `lucent atlas` with its cache entry replaced by a directory: a warning, the atlas rebuilt and cached again (it
// stopped with "<stdout>: cannot write: Is a directory").
TEST(CliInputFiles, AtlasRebuildsOverACacheEntryThatIsADirectory) {
  lucent::test::TempCacheDir cache_dir;
  const std::string env = "LUCENT_CACHE_DIR=" + cache_dir.path().string();
  ASSERT_EQ(run_cli("atlas --size 64", env).exit_code, 0);
  fs::path entry;
  for (const auto& e : fs::recursive_directory_iterator(cache_dir.path()))
    if (e.is_regular_file() && e.path().extension() == ".bin") entry = e.path();
  ASSERT_FALSE(entry.empty());
  fs::remove(entry);
  fs::create_directories(entry / "inside");
  auto r = run_cli("atlas --size 64", env + " " + kNoHang);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("lucent: warning: " + entry.string() +
                          ": precompute cache entry is a directory, not a file; removed and recomputed\n"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::is_regular_file(entry));
}

}  // namespace
