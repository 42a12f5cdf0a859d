// fuzz_support.h: what the libFuzzer targets share: a private temporary folder for the inputs they write to
// files (the loaders read files), removed when the process exits.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace lucent::fuzz {

inline const std::filesystem::path& temp_dir() {
  static const std::filesystem::path dir = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "lucent-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) std::abort();
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(temp_dir(), ignored);
    });
    return std::filesystem::path(pattern);
  }();
  return dir;
}

// Writes the bytes to <temp dir>/input<extension> and returns the path.
inline std::string write_input(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const std::string path = (temp_dir() / ("input" + extension)).string();
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
  return path;
}

}  // namespace lucent::fuzz
