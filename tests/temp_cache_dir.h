// temp_cache_dir.h: a fresh precompute-cache folder for one test: LUCENT_CACHE_DIR points at a new temporary
// directory and the cache is enabled; both restored and the folder removed after.
#pragma once
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <system_error>

#include "cache/precompute_cache.h"

namespace lucent::test {

class TempCacheDir {
 public:
  TempCacheDir() : dir_(std::filesystem::temp_directory_path() / ("lucent_test_cache_" + std::to_string(std::random_device{}()))) {
    if (const char* old = std::getenv("LUCENT_CACHE_DIR")) old_ = old;
    setenv("LUCENT_CACHE_DIR", dir_.c_str(), 1);
    cache::set_enabled(true);
  }
  ~TempCacheDir() {
    cache::set_enabled(true);
    if (old_) setenv("LUCENT_CACHE_DIR", old_->c_str(), 1);
    else unsetenv("LUCENT_CACHE_DIR");
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  TempCacheDir(const TempCacheDir&) = delete;
  TempCacheDir& operator=(const TempCacheDir&) = delete;

  const std::filesystem::path& path() const { return dir_; }
  // Files under the folder (cache entries; temporary files of an interrupted write would count too).
  std::size_t entry_count() const {
    std::size_t n = 0;
    std::error_code ec;
    for (std::filesystem::recursive_directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec))
      n += it->is_regular_file() ? 1 : 0;
    return n;
  }

 private:
  std::filesystem::path dir_;
  std::optional<std::string> old_;
};

}  // namespace lucent::test
