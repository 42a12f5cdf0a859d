// ply_size_check.h: refuses a PLY file whose header declares more data than the file holds, before the
// importer allocates for the declared counts or reads past the end of the data.
#pragma once
#include <string>

namespace lucent {

// Does nothing unless the file's first line is "ply" (whatever its extension: the importer recognises PLY by
// its content too). Throws lucent::Error("<path>: ...") when the header is malformed; when the declared element
// counts times the least bytes each element takes exceed the data after the header (binary: the sizes of its
// scalar properties and of its list counts; ASCII: one character and one separator per value); and, for binary
// files with list properties, when the lists, read one by one, run past the end of the file.
void check_ply_size(const std::string& path);

}  // namespace lucent
