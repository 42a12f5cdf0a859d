// input_file.cpp: see input_file.h.
#include "io/input_file.h"

#include <sys/stat.h>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent {

std::string non_regular_file_kind(const std::string& path) {
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0 || S_ISREG(s.st_mode)) return "";
  if (S_ISDIR(s.st_mode)) return "a directory";
  if (S_ISFIFO(s.st_mode)) return "a FIFO";
  if (S_ISCHR(s.st_mode)) return "a character device";
  if (S_ISBLK(s.st_mode)) return "a block device";
  if (S_ISSOCK(s.st_mode)) return "a socket";
  return "a special file";
}

void require_regular_file(const std::string& path) {
  if (const std::string kind = non_regular_file_kind(path); !kind.empty())
    throw Error(fmt::format("{}: is {}, not a regular file", path, kind));
}

}  // namespace lucent
