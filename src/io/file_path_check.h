// file_path_check.h: file names as the operating system takes them. A path is handed to open() as a C string, so
// a NUL byte in it (possible in JSON, "a.obj\u0000.png", and in Python strings) would silently cut it: the file
// opened would not be the one named, and an extension check would look at another name than the one opened.
#pragma once
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "io/printable_text.h"
#include "lucent/error.h"

namespace lucent {

// "" when `path` can name a file, else the problem ("the file path holds a NUL byte (byte 5), which no file name
// can").
inline std::string file_path_problem(std::string_view path) {
  if (const std::size_t nul = path.find('\0'); nul != std::string_view::npos)
    return fmt::format("the file path holds a NUL byte (byte {}), which no file name can", nul);
  return "";
}

// Throws lucent::Error("<path, unprintable bytes as \xNN>: <problem>") when `path` cannot name a file.
inline void check_file_path(std::string_view path) {
  if (const std::string problem = file_path_problem(path); !problem.empty())
    throw Error(fmt::format("{}: {}", printable_text(path), problem));
}

}  // namespace lucent
