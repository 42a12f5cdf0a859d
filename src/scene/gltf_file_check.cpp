// gltf_file_check.cpp: see gltf_file_check.h.
#include "scene/gltf_file_check.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include "io/input_file.h"
#include "io/printable_text.h"
#include "lucent/error.h"
#include "params/param_json.h"

namespace lucent {
namespace {

using nlohmann::json;

// The extensions lucent reads (materials: scene/gltf_material.cpp; lights: its scene export); a file that requires
// any other is refused, as the specification asks of a loader.
constexpr std::array<std::string_view, 7> kGltfReadExtensions = {
    "KHR_materials_volume",   "KHR_materials_transmission",         "KHR_materials_ior",
    "KHR_lights_punctual",    "KHR_materials_diffuse_transmission", "KHR_materials_volume_scatter",
    "KHR_texture_transform"};

// A file at least this large that stores less than an eighth of its size is sparse: its size is no promise of data.
constexpr std::uintmax_t kSparseCheckBytes = std::uintmax_t{1} << 24;

// A member of a JSON object, or null when absent (or when `object` is not an object).
const json* member(const json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

// A whole number >= 0 at `key`, or nullopt.
std::optional<std::uint64_t> whole(const json& object, const char* key) {
  const json* v = member(object, key);
  if (!v || !v->is_number_unsigned()) return std::nullopt;
  return v->get<std::uint64_t>();
}

[[noreturn]] void refuse(const std::string& path, const std::string& pointer, const std::string& problem) {
  throw Error(fmt::format("{}: {}: {}", path, pointer, problem));
}

std::uint32_t u32_at(std::string_view bytes, std::size_t offset) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + offset, 4);
  return v;
}

std::optional<std::string> base64_decoded(std::string_view text) {
  auto digit = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string out;
  std::uint32_t bits = 0;
  int count = 0;
  for (char c : text) {
    if (c == '=') break;
    const int d = digit(c);
    if (d < 0) return std::nullopt;
    bits = (bits << 6) | static_cast<std::uint32_t>(d);
    if (++count == 4) {
      out.push_back(static_cast<char>(bits >> 16)), out.push_back(static_cast<char>(bits >> 8));
      out.push_back(static_cast<char>(bits)), bits = 0, count = 0;
    }
  }
  if (count == 2) out.push_back(static_cast<char>(bits >> 4));
  if (count == 3) out.push_back(static_cast<char>(bits >> 10)), out.push_back(static_cast<char>(bits >> 2));
  return out;
}

// A byteOffset or byteLength: absent (0) or a non-negative whole number.
std::uint64_t byte_count(const json& object, const char* key, const std::string& path, const std::string& at) {
  const json* found = member(object, key);
  if (!found) return 0;
  const json& v = *found;
  if (!v.is_number_integer() || (v.is_number_integer() && !v.is_number_unsigned() && v.get<std::int64_t>() < 0))
    refuse(path, at + "/" + key, fmt::format("{} is not a non-negative whole number of bytes", v.dump()));
  return v.get<std::uint64_t>();
}

struct Container {
  std::string json_text;
  std::optional<std::string> bin;  // a GLB's BIN chunk
};

std::optional<Container> container_of(const std::string& path, const std::string& bytes) {
  if (bytes.size() < 4 || std::memcmp(bytes.data(), "glTF", 4) != 0) return Container{bytes, std::nullopt};
  if (bytes.size() < 20)
    throw Error(fmt::format("{}: cannot read glTF: a truncated GLB: {} bytes, fewer than a header and a chunk's 20",
                            path, bytes.size()));
  if (u32_at(bytes, 4) != 2) return std::nullopt;  // another version: the reader names it
  const std::uint64_t length = u32_at(bytes, 8);
  if (length > bytes.size())
    throw Error(fmt::format("{}: cannot read glTF: the GLB header declares {} bytes; the file holds {}", path, length,
                            bytes.size()));
  Container c;
  std::size_t offset = 12;
  for (int chunk = 0; offset + 8 <= length; ++chunk) {
    const std::uint64_t size = u32_at(bytes, offset);
    if (offset + 8 + size > length)
      throw Error(fmt::format("{}: cannot read glTF: GLB chunk {} declares {} bytes; {} remain in the file", path,
                              chunk, size, length - offset - 8));
    const std::string data = bytes.substr(offset + 8, size);
    if (chunk == 0) c.json_text = data;
    else if (chunk == 1) c.bin = data;
    offset += 8 + static_cast<std::size_t>(size);
  }
  return c;
}

// The bytes of buffer `i` (after its file's checks), or nullopt where they cannot be had (the reader reports it).
std::optional<std::string> buffer_bytes(const json& buffer, const Container& c, const std::filesystem::path& folder,
                                        const std::string& path, const std::string& at) {
  const std::uint64_t declared = byte_count(buffer, "byteLength", path, at);
  const json* uri_value = member(buffer, "uri");
  if (!uri_value) return c.bin;
  if (!uri_value->is_string()) return std::nullopt;
  const std::string uri = uri_value->get<std::string>();
  if (uri.rfind("data:", 0) == 0) {
    const std::size_t comma = uri.find(',');
    if (comma == std::string::npos) return std::nullopt;
    return base64_decoded(std::string_view(uri).substr(comma + 1));
  }
  const std::string file = (folder / uri).string();
  if (const std::string kind = non_regular_file_kind(file); !kind.empty())
    refuse(path, at + "/uri", fmt::format("'{}' is {}, not a regular file", printable_text(uri), kind));
  struct stat s {};
  if (::stat(file.c_str(), &s) != 0) return std::nullopt;  // missing: the reader says so
  const auto size = static_cast<std::uintmax_t>(s.st_size);
  if (size < declared)
    refuse(path, at + "/byteLength", fmt::format("{} bytes; '{}' holds {}", declared, printable_text(uri), size));
  if (size >= kSparseCheckBytes && static_cast<std::uintmax_t>(s.st_blocks) * 512u < size / 8)
    refuse(path, at + "/uri",
           fmt::format("'{}' is a sparse file: {} bytes long, {} stored", printable_text(uri), size,
                       static_cast<std::uintmax_t>(s.st_blocks) * 512u));
  std::ifstream in(file, std::ios::binary);
  std::string bytes(static_cast<std::size_t>(std::min<std::uintmax_t>(size, declared)), '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) return std::nullopt;
  return bytes;
}

// The indices of accessor `index` as whole numbers, or nullopt where the file does not say them plainly (sparse
// accessors, ranges outside their view: the reader reports those).
std::optional<std::vector<std::uint32_t>> index_values(const json& doc, std::size_t index,
                                                       const std::vector<std::optional<std::string>>& buffers,
                                                       const std::string& path) {
  const json* accessors = member(doc, "accessors");
  const json* views = member(doc, "bufferViews");
  if (!accessors || !accessors->is_array() || index >= accessors->size() || !views || !views->is_array())
    return std::nullopt;
  const json& a = (*accessors)[index];
  const std::optional<std::uint64_t> view_index = whole(a, "bufferView"), type = whole(a, "componentType"),
                                     count = whole(a, "count");
  if (!view_index || !type || !count || member(a, "sparse") || *view_index >= views->size()) return std::nullopt;
  const std::size_t size = *type == 5121 ? 1 : *type == 5123 ? 2 : *type == 5125 ? 4 : 0;
  if (size == 0) return std::nullopt;
  const json& view = (*views)[static_cast<std::size_t>(*view_index)];
  const std::optional<std::uint64_t> buffer = view.is_object() && !member(view, "buffer") ? 0 : whole(view, "buffer");
  if (!view.is_object() || !buffer || *buffer >= buffers.size() || !buffers[*buffer]) return std::nullopt;
  const std::string view_at = fmt::format("/bufferViews/{}", *view_index);
  const std::uint64_t view_start = byte_count(view, "byteOffset", path, view_at);
  const std::uint64_t offset = view_start + byte_count(a, "byteOffset", path, fmt::format("/accessors/{}", index));
  const std::uint64_t view_end = view_start + byte_count(view, "byteLength", path, view_at);
  const std::uint64_t stride = std::max<std::uint64_t>(size, byte_count(view, "byteStride", path, view_at));
  const std::string& bytes = *buffers[*buffer];
  if (*count == 0) return std::vector<std::uint32_t>{};
  if (*count > bytes.size()) return std::nullopt;
  const std::uint64_t last = offset + (*count - 1) * stride + size;
  if (last > view_end || last > bytes.size()) return std::nullopt;
  std::vector<std::uint32_t> values(static_cast<std::size_t>(*count));
  for (std::size_t k = 0; k < values.size(); ++k) {
    std::uint32_t v = 0;
    std::memcpy(&v, bytes.data() + offset + k * stride, size);  // little-endian, as glTF and the host
    values[k] = v;
  }
  return values;
}

}  // namespace

void check_gltf_file(const std::string& path) {
  require_regular_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) return;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::optional<Container> c = container_of(path, bytes);
  if (!c) return;
  // Named as a scene file's JSON errors are (line, column, what; glTF's JSON has no NaN or Infinity literals).
  json doc;
  try {
    doc = parse_json(c->json_text, {path, ""});
  } catch (const Error& e) {  // "<path>: malformed JSON: ..." as "<path>: cannot read glTF: malformed JSON: ..."
    const std::string message = e.what();
    throw Error(fmt::format("{}: cannot read glTF: {}", path,
                            message.rfind(path + ": ", 0) == 0 ? message.substr(path.size() + 2) : message));
  }
  if (!doc.is_object()) throw Error(fmt::format("{}: cannot read glTF: its JSON is not an object", path));
  if (const json* list = member(doc, "extensionsRequired"); list && list->is_array()) {
    const json& required = *list;
    for (std::size_t i = 0; i < required.size(); ++i) {
      const std::string name = required[i].is_string() ? required[i].get<std::string>() : required[i].dump();
      if (std::find(kGltfReadExtensions.begin(), kGltfReadExtensions.end(), name) == kGltfReadExtensions.end())
        refuse(path, fmt::format("/extensionsRequired/{}", i),
               fmt::format("the file requires '{}', which lucent does not read (a loader must refuse such a file)",
                           printable_text(name)));
    }
  }
  for (const char* key : {"bufferViews", "accessors"})
    if (const json* list = member(doc, key); list && list->is_array())
      for (std::size_t i = 0; i < list->size(); ++i)
        if ((*list)[i].is_object()) byte_count((*list)[i], "byteOffset", path, fmt::format("/{}/{}", key, i));
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (const json* images = member(doc, "images"); images && images->is_array())
    for (std::size_t i = 0; i < images->size(); ++i) {
      const json* uri_value = member((*images)[i], "uri");
      if (!uri_value || !uri_value->is_string()) continue;
      const std::string uri = uri_value->get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      if (const std::string kind = non_regular_file_kind((folder / uri).string()); !kind.empty())
        refuse(path, fmt::format("/images/{}/uri", i), fmt::format("'{}' is {}, not a regular file", printable_text(uri), kind));
    }
  std::vector<std::optional<std::string>> buffers;
  if (const json* list = member(doc, "buffers"); list && list->is_array())
    for (std::size_t i = 0; i < list->size(); ++i)
      buffers.push_back((*list)[i].is_object()
                            ? buffer_bytes((*list)[i], *c, folder, path, fmt::format("/buffers/{}", i))
                            : std::nullopt);
  const json* meshes = member(doc, "meshes");
  const json* accessors = member(doc, "accessors");
  if (!meshes || !meshes->is_array() || !accessors || !accessors->is_array()) return;
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const json* primitives = member((*meshes)[m], "primitives");
    if (!primitives || !primitives->is_array()) continue;
    for (std::size_t p = 0; p < primitives->size(); ++p) {
      const json& primitive = (*primitives)[p];
      const json* attributes = member(primitive, "attributes");
      // Absent or malformed: past every accessor (GCC 12 misreads an optional here as maybe uninitialized).
      constexpr std::uint64_t kNone = ~std::uint64_t{0};
      const std::uint64_t index_accessor = whole(primitive, "indices").value_or(kNone);
      const std::uint64_t position = attributes ? whole(*attributes, "POSITION").value_or(kNone) : kNone;
      if (const json* mode = member(primitive, "mode"); mode && !(mode->is_number_unsigned() && mode->get<std::uint64_t>() <= 6))
        refuse(path, fmt::format("/meshes/{}/primitives/{}/mode", m, p),
               fmt::format("{} is not a primitive mode (0 points to 6 triangle fan)", mode->dump()));
      if (index_accessor == kNone || position >= accessors->size()) continue;
      const std::optional<std::uint64_t> count = whole((*accessors)[static_cast<std::size_t>(position)], "count");
      if (!count) continue;
      const std::uint64_t vertices = *count;
      const std::optional<std::vector<std::uint32_t>> indices =
          index_values(doc, static_cast<std::size_t>(index_accessor), buffers, path);
      if (!indices) continue;
      for (std::size_t k = 0; k < indices->size(); ++k)
        if ((*indices)[k] >= vertices)
          refuse(path, fmt::format("/meshes/{}/primitives/{}/indices", m, p),
                 fmt::format("index {} (element {}) is past the last of the {} vertices of its POSITION accessor",
                             (*indices)[k], k, vertices));
    }
  }
}

}  // namespace lucent
