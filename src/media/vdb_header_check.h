// vdb_header_check.h: refuses an OpenVDB file whose header or grid descriptors do not fit in the file, before
// OpenVDB reads it (OpenVDB sizes its reads and allocations by what the file declares: the first 200 bytes of a
// valid file made it allocate 20 GB).
#pragma once
#include <string>

namespace lucent {

// Walks the file's header (magic number, format version, UUID), its file-level metadata and its grid descriptors
// (name, type, the grid's byte offsets) as OpenVDB lays them out, checking each length and offset against the
// file's size. Throws lucent::Error("<path>: ...") when the file cannot be opened, does not start with the
// OpenVDB magic number, ends inside the header or a descriptor, or a descriptor places its grid outside the file
// (a truncated file). Format versions outside 211..224 and files written without grid offsets (to a stream) are
// left to OpenVDB.
void check_vdb_header(const std::string& path);

}  // namespace lucent
