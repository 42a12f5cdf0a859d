// vdb_header_check.cpp: the layout checks of vdb_header_check.h. Layout (OpenVDB 10, io/Archive.cc, io/File.cc,
// io/GridDescriptor.cc; little-endian): int64 magic 0x56444220, uint32 format version, uint32 x 2 library version,
// char "has grid offsets" (version >= 212), char "compressed" (220 <= version < 222), the UUID (36 characters from
// version 218, else 16 bytes); file metadata: uint32 count, then per entry name, type name (strings: uint32 length
// + bytes) and uint32 size + value bytes; int32 grid count; per grid a descriptor: unique name, type name, the
// instance parent's name (version >= 216), int64 grid, block and end offsets; the next descriptor starts at the
// end offset.
#include "media/vdb_header_check.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>

#include <fmt/format.h>

#include "io/file_path_check.h"
#include "io/printable_text.h"
#include "lucent/error.h"

namespace lucent {
namespace {

constexpr std::uint64_t kVdbMagic = 0x56444220;  // OPENVDB_MAGIC
constexpr std::uint32_t kFirstCheckedVersion = 211, kLastCheckedVersion = 224;
constexpr std::uint32_t kVersionGridOffsets = 212, kVersionSelectiveCompression = 220,
                        kVersionNodeMaskCompression = 222, kVersionGridInstancing = 216, kVersionTextUuid = 218;

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw Error(fmt::format("{}: {}", path, problem));
}

// Reads the file front to back, every read checked against the file's size.
class VdbCursor {
 public:
  VdbCursor(const std::string& path, std::uint64_t size) : path_(path), in_(path, std::ios::binary), size_(size) {
    if (!in_) fail(path, "cannot open the VDB file");
  }

  std::uint64_t position() const { return position_; }

  void bytes(void* out, std::uint64_t count, std::string_view what) {
    if (count > size_ - position_)
      fail(path_, fmt::format("the file ends inside {} ({} bytes; truncated or not a VDB file)", what, size_));
    in_.read(static_cast<char*>(out), static_cast<std::streamsize>(count));
    if (static_cast<std::uint64_t>(in_.gcount()) != count) fail(path_, "cannot read the VDB file");
    position_ += count;
  }

  template <class T>
  T value(std::string_view what) {
    T v;
    bytes(&v, sizeof v, what);
    return v;
  }

  void skip(std::uint64_t count, std::string_view what) {
    if (count > size_ - position_)
      fail(path_, fmt::format("the file ends inside {} ({} bytes; truncated or not a VDB file)", what, size_));
    seek(position_ + count);
  }

  // A string: uint32 length, then the bytes (lengths past the end of the file are refused before reading).
  std::string text(std::string_view what) {
    const auto length = value<std::uint32_t>(what);
    if (length > size_ - position_)
      fail(path_, fmt::format("the file ends inside {} ({} bytes; truncated or not a VDB file)", what, size_));
    std::string s(length, '\0');
    bytes(s.data(), length, what);
    return s;
  }

  void seek(std::uint64_t position) {
    in_.seekg(static_cast<std::streamoff>(position));
    position_ = position;
  }

 private:
  const std::string& path_;
  std::ifstream in_;
  std::uint64_t size_;
  std::uint64_t position_ = 0;
};

}  // namespace

void check_vdb_header(const std::string& path) {
  check_file_path(path);
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) fail(path, "cannot open the VDB file");
  VdbCursor in(path, size);
  std::uint64_t magic = 0;
  if (size < sizeof magic) fail(path, "not a VDB file (no OpenVDB magic number)");
  in.bytes(&magic, sizeof magic, "the header");
  if (magic != kVdbMagic) fail(path, "not a VDB file (no OpenVDB magic number)");
  const auto version = in.value<std::uint32_t>("the header");
  if (version < kFirstCheckedVersion || version > kLastCheckedVersion) return;
  in.skip(8, "the header");  // library version
  bool offsets = true;
  if (version >= kVersionGridOffsets) offsets = in.value<char>("the header") != 0;
  if (version >= kVersionSelectiveCompression && version < kVersionNodeMaskCompression) in.skip(1, "the header");
  in.skip(version >= kVersionTextUuid ? 36 : 16, "the header");
  const auto metadata = in.value<std::uint32_t>("the file metadata");
  for (std::uint32_t i = 0; i < metadata; ++i) {
    in.text("the file metadata");
    in.text("the file metadata");
    in.skip(in.value<std::uint32_t>("the file metadata"), "the file metadata");
  }
  const auto grids = in.value<std::int32_t>("the grid count");
  if (grids < 0) fail(path, fmt::format("grid count {} is negative (not a VDB file)", grids));
  if (!offsets) return;  // grids follow one another without offsets: nothing more to check before reading them
  for (std::int32_t g = 0; g < grids; ++g) {
    const std::string name = printable_text(in.text("a grid descriptor"));
    in.text("a grid descriptor");
    if (version >= kVersionGridInstancing) in.text("a grid descriptor");
    const auto grid = in.value<std::int64_t>("a grid descriptor");
    const auto block = in.value<std::int64_t>("a grid descriptor");
    const auto end = in.value<std::int64_t>("a grid descriptor");
    if (end < 0 || static_cast<std::uint64_t>(end) > size)
      fail(path, fmt::format("grid '{}' ends at byte {}, past the end of the file ({} bytes; truncated)", name, end,
                             size));
    if (grid < 0 || static_cast<std::uint64_t>(grid) < in.position() || grid > end ||
        (block != 0 && (block < grid || block > end)))
      fail(path, fmt::format("grid '{}' has inconsistent offsets (grid {}, data {}, end {}; not a VDB file)", name,
                             grid, block, end));
    in.seek(static_cast<std::uint64_t>(end));
  }
}

}  // namespace lucent
