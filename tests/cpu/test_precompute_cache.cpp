// test_precompute_cache.cpp: the on-disk precompute cache: the hash against the reference's known answer and
// streamed in pieces, keys that tell inputs apart, round trips, damaged and truncated entries (ignored with one
// warning), the size cap (least recently used first), the switch, the unwritable directory, the folder chosen
// from LUCENT_CACHE_DIR, XDG_CACHE_HOME and HOME.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cache/precompute_cache.h"
#include "lucent/material.h"
#include "lucent/mesh.h"

namespace {

namespace cache = lucent::cache;
namespace fs = std::filesystem;

std::vector<std::byte> bytes_of(const std::string& text) {
  const auto* data = reinterpret_cast<const std::byte*>(text.data());
  return {data, data + text.size()};
}

// Sets an environment variable for one test, restoring it after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) setenv(name, value, 1);
    else unsetenv(name);
  }
  ~ScopedEnv() {
    if (old_) setenv(name_, old_->c_str(), 1);
    else unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// A fresh cache directory (LUCENT_CACHE_DIR) per test, the default settings, removed after.
class PrecomputeCache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lucent_test_cache_" + std::to_string(std::random_device{}()));
    env_.emplace("LUCENT_CACHE_DIR", dir_.c_str());
    cache::set_enabled(true);
    cache::set_max_bytes(cache::kDefaultMaxBytes);
  }
  void TearDown() override {
    cache::set_enabled(true);
    cache::set_max_bytes(cache::kDefaultMaxBytes);
    env_.reset();
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::size_t entry_count() const {
    std::size_t n = 0;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec))
      n += it->is_regular_file() ? 1 : 0;
    return n;
  }

  fs::path dir_;
  std::optional<ScopedEnv> env_;
};

cache::Key key_of(const std::string& name) {
  cache::Key key("test-kind", 1);
  key.text(name);
  return key;
}

// ---- the hash --------------------------------------------------------------------------------------------------

TEST(CacheHash, MatchesMurmurHash3KnownAnswers) {
  // MurmurHash3_x64_128, seed 0 (SMHasher's reference); h1 and h2 as the reference writes them.
  cache::Digest fox = cache::hash_bytes(bytes_of("The quick brown fox jumps over the lazy dog"));
  EXPECT_EQ(fox.hex(), "e34bbc7bbc071b6c7a433ca9c49a9347");
  EXPECT_EQ(cache::hash_bytes({}).hex(), "00000000000000000000000000000000");
}

TEST(CacheHash, PiecesGiveTheWholeStreamsDigest) {
  std::string text;
  for (int i = 0; i < 300; ++i) text += static_cast<char>('a' + (i * 7) % 26);
  const cache::Digest whole = cache::hash_bytes(bytes_of(text));
  std::mt19937 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    cache::Hasher hasher;
    std::vector<std::byte> all = bytes_of(text);
    for (std::size_t at = 0; at < all.size();) {
      std::size_t n = std::min<std::size_t>(all.size() - at, rng() % 40);
      hasher.update(std::span(all).subspan(at, n));
      at += n;
    }
    ASSERT_EQ(hasher.finish(), whole) << "trial " << trial;
  }
  for (std::size_t length = 0; length <= 40; ++length)  // every tail length against a one-byte-at-a-time stream
  {
    cache::Hasher bytewise;
    std::vector<std::byte> part = bytes_of(text.substr(0, length));
    for (std::byte b : part) bytewise.update(std::span(&b, 1));
    ASSERT_EQ(bytewise.finish(), cache::hash_bytes(part)) << "length " << length;
  }
}

// ---- keys --------------------------------------------------------------------------------------------------------

TEST(CacheKey, TellsInputsApart) {
  auto digest = [](auto&& fill) {
    cache::Key key("k", 1);
    fill(key);
    return key.digest();
  };
  EXPECT_NE(digest([](cache::Key& k) { k.text("ab").text("c"); }), digest([](cache::Key& k) { k.text("a").text("bc"); }));
  EXPECT_NE(digest([](cache::Key& k) { k.integer(1); }), digest([](cache::Key& k) { k.number(1.0); }));
  EXPECT_EQ(digest([](cache::Key& k) { k.number(0.0); }), digest([](cache::Key& k) { k.number(-0.0); }));
  EXPECT_NE(cache::Key("k", 1).digest(), cache::Key("k", 2).digest());
  EXPECT_NE(cache::Key("k", 1).digest(), cache::Key("l", 1).digest());

  lucent::TriangleMesh sphere = lucent::make_sphere(1.0f, 4, 8), moved_uv = sphere, no_uv = sphere;
  moved_uv.uvs[3].x += 0.01f;
  no_uv.uvs.clear();
  const auto mesh_digest = [&](const lucent::TriangleMesh& m) { return digest([&](cache::Key& k) { k.mesh(m); }); };
  EXPECT_EQ(mesh_digest(sphere), mesh_digest(lucent::make_sphere(1.0f, 4, 8)));  // deterministic
  EXPECT_NE(mesh_digest(sphere), mesh_digest(moved_uv));
  EXPECT_NE(mesh_digest(sphere), mesh_digest(no_uv));

  lucent::Material skin, renamed, thicker;
  skin.sigma_a = glm::vec3(0.03f);
  skin.sigma_s = glm::vec3(1.0f);
  renamed = thicker = skin;
  renamed.name = "other name";
  thicker.sigma_a.y = 0.04f;
  const auto material_digest = [&](const lucent::Material& m) { return digest([&](cache::Key& k) { k.material(m); }); };
  EXPECT_EQ(material_digest(skin), material_digest(renamed));  // the name is no input of the physics
  EXPECT_NE(material_digest(skin), material_digest(thicker));

  lucent::ParamValues a, b, c;
  a.set("K", 8.0), a.set("name", std::string("x"));
  b.set("name", std::string("x")), b.set("K", 8.0);
  c.set("K", 9.0), c.set("name", std::string("x"));
  const auto params_digest = [&](const lucent::ParamValues& v) { return digest([&](cache::Key& k) { k.params(v); }); };
  EXPECT_EQ(params_digest(a), params_digest(b));  // the order they were set in does not matter
  EXPECT_NE(params_digest(a), params_digest(c));
}

TEST(CacheKey, KindMustBeAFolderName) {
  EXPECT_THROW(cache::Key("../escape", 1), std::invalid_argument);
  EXPECT_THROW(cache::Key("", 1), std::invalid_argument);
  EXPECT_NO_THROW(cache::Key("radiosity-maps.v2_x", 1));
}

// ---- entries -----------------------------------------------------------------------------------------------------

TEST_F(PrecomputeCache, RoundTrip) {
  EXPECT_EQ(cache::load(key_of("a")), std::nullopt);
  cache::store(key_of("a"), bytes_of("payload of a"));
  cache::store(key_of("empty"), {});
  EXPECT_EQ(cache::load(key_of("a")), bytes_of("payload of a"));
  EXPECT_EQ(cache::load(key_of("empty")), std::vector<std::byte>{});
  EXPECT_EQ(cache::load(key_of("b")), std::nullopt);
  EXPECT_EQ(cache::entry_path(key_of("a")).parent_path(), dir_ / "test-kind");
  EXPECT_TRUE(fs::exists(cache::entry_path(key_of("a"))));
}

void expect_ignored_with_one_warning(const cache::Key& key, const std::string& why) {
  const fs::path path = cache::entry_path(key);
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(cache::load(key), std::nullopt);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(),
            "lucent: warning: " + path.string() + ": damaged precompute cache entry (" + why + "); recomputing\n");
  EXPECT_FALSE(fs::exists(path));  // removed: the recomputed result takes its place
}

TEST_F(PrecomputeCache, DamagedEntryIsIgnoredWithAWarning) {
  cache::store(key_of("a"), bytes_of("payload of a"));
  const fs::path path = cache::entry_path(key_of("a"));
  {
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(-3, std::ios::end);
    file.put('X');
  }
  expect_ignored_with_one_warning(key_of("a"), "payload checksum mismatch");
  cache::store(key_of("a"), bytes_of("payload of a"));
  EXPECT_EQ(cache::load(key_of("a")), bytes_of("payload of a"));  // recomputed and stored again
}

TEST_F(PrecomputeCache, TruncatedEntryIsIgnoredWithAWarning) {
  cache::store(key_of("a"), bytes_of("payload of a"));
  const fs::path path = cache::entry_path(key_of("a"));
  fs::resize_file(path, fs::file_size(path) - 1);
  expect_ignored_with_one_warning(key_of("a"), "payload of 11 bytes, the header says 12");
  cache::store(key_of("a"), bytes_of("payload of a"));
  fs::resize_file(path, 20);
  expect_ignored_with_one_warning(key_of("a"), "20 bytes, shorter than the header");
}

TEST_F(PrecomputeCache, EntryUnderAnotherKeysNameIsIgnored) {
  cache::store(key_of("a"), bytes_of("payload of a"));
  fs::create_directories(cache::entry_path(key_of("b")).parent_path());
  fs::copy_file(cache::entry_path(key_of("a")), cache::entry_path(key_of("b")));
  expect_ignored_with_one_warning(key_of("b"), "stored under another key's name");
  EXPECT_EQ(cache::load(key_of("a")), bytes_of("payload of a"));
}

// The cap holds three entries; a fourth evicts the least recently used, where a hit counts as a use.
TEST_F(PrecomputeCache, SizeCapEvictsTheLeastRecentlyUsed) {
  const std::vector<std::byte> payload(1000, std::byte{7});
  cache::store(key_of("probe"), payload);
  const std::uintmax_t entry_bytes = fs::file_size(cache::entry_path(key_of("probe")));
  fs::remove(cache::entry_path(key_of("probe")));
  cache::set_max_bytes(3 * entry_bytes + entry_bytes / 2);

  const auto start = fs::file_time_type::clock::now() - std::chrono::hours(1);
  for (int i = 0; i < 3; ++i) {  // a, b, c used one minute apart (mtime resolution is no concern)
    const std::string name(1, static_cast<char>('a' + i));
    cache::store(key_of(name), payload);
    fs::last_write_time(cache::entry_path(key_of(name)), start + std::chrono::minutes(i));
  }
  ASSERT_TRUE(cache::load(key_of("a")));  // a is now the most recently used: b is the oldest
  cache::store(key_of("d"), payload);
  EXPECT_EQ(entry_count(), 3u);
  EXPECT_TRUE(fs::exists(cache::entry_path(key_of("a"))));
  EXPECT_FALSE(fs::exists(cache::entry_path(key_of("b"))));
  EXPECT_TRUE(fs::exists(cache::entry_path(key_of("c"))));
  EXPECT_TRUE(fs::exists(cache::entry_path(key_of("d"))));

  cache::store(key_of("huge"), std::vector<std::byte>(4 * entry_bytes));  // larger than the cap: not stored
  EXPECT_FALSE(fs::exists(cache::entry_path(key_of("huge"))));
  EXPECT_EQ(entry_count(), 3u);
}

TEST_F(PrecomputeCache, DisabledWritesAndReadsNothing) {
  cache::store(key_of("a"), bytes_of("payload of a"));
  cache::set_enabled(false);
  EXPECT_EQ(cache::load(key_of("a")), std::nullopt);
  cache::store(key_of("b"), bytes_of("payload of b"));
  EXPECT_EQ(entry_count(), 1u);
  EXPECT_FALSE(fs::exists(cache::entry_path(key_of("b"))));
  cache::set_enabled(true);
  EXPECT_EQ(cache::load(key_of("a")), bytes_of("payload of a"));
}

// A cache folder that cannot be created (its parent is a file: refused to root too) is one warning, not an error.
TEST_F(PrecomputeCache, UnwritableDirectoryIsAWarning) {
  fs::create_directories(dir_);
  std::ofstream(dir_ / "file") << "x";
  ScopedEnv inside_a_file("LUCENT_CACHE_DIR", (dir_ / "file" / "cache").c_str());
  ::testing::internal::CaptureStderr();
  EXPECT_NO_THROW(cache::store(key_of("a"), bytes_of("payload of a")));
  EXPECT_NO_THROW(cache::store(key_of("b"), bytes_of("payload of b")));
  const std::string warnings = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(warnings.rfind("lucent: warning: precompute cache not written (", 0), 0u) << warnings;
  EXPECT_NE(warnings.find("the work is not cached\n"), std::string::npos) << warnings;
  EXPECT_EQ(std::count(warnings.begin(), warnings.end(), '\n'), 1) << warnings;  // once, not per store
  EXPECT_EQ(cache::load(key_of("a")), std::nullopt);
}

// ---- where -------------------------------------------------------------------------------------------------------

TEST_F(PrecomputeCache, FolderFromTheEnvironment) {
  EXPECT_EQ(cache::directory(), dir_);
  ScopedEnv no_override("LUCENT_CACHE_DIR", nullptr);
  {
    ScopedEnv xdg("XDG_CACHE_HOME", (dir_ / "xdg").c_str());
    EXPECT_EQ(cache::directory(), dir_ / "xdg" / "lucent");
    cache::store(key_of("a"), bytes_of("payload of a"));
    EXPECT_TRUE(fs::exists(dir_ / "xdg" / "lucent" / "test-kind" / (key_of("a").digest().hex() + ".bin")));
    EXPECT_EQ(cache::load(key_of("a")), bytes_of("payload of a"));
  }
  ScopedEnv home("HOME", (dir_ / "home").c_str());
  {
    ScopedEnv relative_xdg("XDG_CACHE_HOME", "relative/cache");  // not absolute: ignored (XDG base directories)
    EXPECT_EQ(cache::directory(), dir_ / "home" / ".cache" / "lucent");
  }
  ScopedEnv no_xdg("XDG_CACHE_HOME", nullptr);
  EXPECT_EQ(cache::directory(), dir_ / "home" / ".cache" / "lucent");
  ScopedEnv no_home("HOME", nullptr);
  EXPECT_EQ(cache::directory(), fs::path());
  EXPECT_NO_THROW(cache::store(key_of("a"), bytes_of("payload of a")));  // nowhere to cache: nothing happens
  EXPECT_EQ(cache::load(key_of("b")), std::nullopt);
}

}  // namespace
