// input_file.h: what lucent accepts as an input file. Every reader checks its path first: a FIFO would block the
// open (or the read) forever, a device would never end, and a directory reads as an empty or malformed file.
#pragma once
#include <string>

namespace lucent {

// Throws lucent::Error("<path>: is a FIFO, not a regular file") unless `path` names a regular file (symbolic links
// followed). A path that does not exist passes: the reader reports that in its own words.
void require_regular_file(const std::string& path);

// What `path` is when it is not a regular file ("a directory", "a FIFO", "a character device", ...); "" for a
// regular file and for a path that does not exist.
std::string non_regular_file_kind(const std::string& path);

}  // namespace lucent
