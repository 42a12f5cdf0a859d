// file_watcher.h: notices that a file changed on disk by polling its modification time and size (no inotify:
// editors that replace the file by renaming a new one over it are seen the same way).
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>

namespace lucent::viewer {

class FileWatcher {
 public:
  FileWatcher() = default;
  explicit FileWatcher(std::string path);
  // True once after each change of the file's mtime or size since the last call (or construction); a file that
  // disappears is not a change (an editor saving it), one that comes back is.
  bool changed();
  const std::string& path() const { return path_; }
  bool active() const { return !path_.empty(); }

 private:
  struct Stamp {
    bool exists = false;
    std::filesystem::file_time_type mtime{};
    std::uintmax_t size = 0;
    bool operator==(const Stamp&) const = default;
  };
  static Stamp stamp_of(const std::string& path);
  std::string path_;
  Stamp last_;
};

}  // namespace lucent::viewer
