// file_watcher.cpp: mtime and size polling.
#include "viewer/file_watcher.h"

#include <system_error>

namespace lucent::viewer {

FileWatcher::FileWatcher(std::string path) : path_(std::move(path)), last_(stamp_of(path_)) {}

FileWatcher::Stamp FileWatcher::stamp_of(const std::string& path) {
  std::error_code ec;
  Stamp stamp;
  stamp.mtime = std::filesystem::last_write_time(path, ec);
  if (ec) return {};
  stamp.size = std::filesystem::file_size(path, ec);
  if (ec) return {};
  stamp.exists = true;
  return stamp;
}

bool FileWatcher::changed() {
  if (path_.empty()) return false;
  Stamp now = stamp_of(path_);
  if (!now.exists) return false;  // mid-save; keep the last stamp so the new file counts as a change
  if (now == last_) return false;
  last_ = now;
  return true;
}

}  // namespace lucent::viewer
