// ply_size_check.cpp: PLY header parsing and the size checks of ply_size_check.h. Format: Greg Turk, "The PLY
// Polygon File Format" (1994), with the type names of PLY 1.0 (char, uchar, ..., double) and the sized aliases
// (int8, ..., float64) that the importer also accepts, case-insensitively.
#include "scene/ply_size_check.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "lucent/error.h"
#include "io/printable_text.h"

namespace lucent {
namespace {

constexpr std::size_t kMaxHeaderBytes = 1 << 20;
constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyProperty {
  int size = 0;        // bytes of the scalar, or of each list item
  int count_size = 0;  // bytes of the list length; 0 for a scalar
  bool count_signed = false;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::uint64_t data_offset = 0;  // first byte after the end_header line
};

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  std::uint64_t sum = 0;
  return __builtin_add_overflow(a, b, &sum) ? kSaturated : sum;
}

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
  std::uint64_t product = 0;
  return __builtin_mul_overflow(a, b, &product) ? kSaturated : product;
}

std::string lowercase(std::string_view text) {
  std::string lower(text);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower;
}

// Bytes of a PLY scalar type; 0 when the name is none.
int type_size(std::string_view name) {
  const std::string type = lowercase(name);
  for (const char* t : {"char", "uchar", "int8", "uint8"})
    if (type == t) return 1;
  for (const char* t : {"short", "ushort", "int16", "uint16"})
    if (type == t) return 2;
  for (const char* t : {"int", "uint", "int32", "uint32", "float", "float32"})
    if (type == t) return 4;
  for (const char* t : {"double", "float64"})
    if (type == t) return 8;
  return 0;
}

bool is_integer_type(std::string_view name) {
  const std::string type = lowercase(name);
  return type != "float" && type != "float32" && type != "double" && type != "float64";
}

bool is_signed_type(std::string_view name) {
  const std::string type = lowercase(name);
  return type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" || type == "int32";
}

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t begin = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > begin) words.push_back(line.substr(begin, i - begin));
  }
  return words;
}

class HeaderParser {
 public:
  explicit HeaderParser(const std::string& path) : path_(path) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw Error(fmt::format("{}: malformed PLY header: {}", path_, problem));
  }

  void parse_format(const std::vector<std::string_view>& words, PlyHeader& header) {
    if (words.size() < 2) fail("'format' needs ascii, binary_little_endian or binary_big_endian");
    const std::string format = lowercase(words[1]);
    if (format == "ascii")
      header.format = PlyFormat::Ascii;
    else if (format == "binary_little_endian")
      header.format = PlyFormat::BinaryLittleEndian;
    else if (format == "binary_big_endian")
      header.format = PlyFormat::BinaryBigEndian;
    else
      fail(fmt::format("unknown format '{}'", printable_text(words[1], 64)));
    has_format_ = true;
  }

  void parse_element(const std::vector<std::string_view>& words, PlyHeader& header) {
    if (words.size() != 3) fail("'element' needs a name and a count");
    PlyElement element;
    element.name = std::string(words[1]);
    const char* end = words[2].data() + words[2].size();
    const auto [last, error] = std::from_chars(words[2].data(), end, element.count);
    if (error != std::errc() || last != end)
      fail(fmt::format("element '{}' has count '{}', not a whole number below 2^64", printable_text(words[1], 64),
                       printable_text(words[2], 64)));
    header.elements.push_back(std::move(element));
  }

  void parse_property(const std::vector<std::string_view>& words, PlyHeader& header) {
    if (header.elements.empty()) fail("'property' before any 'element'");
    PlyProperty property;
    const bool list = words.size() >= 2 && lowercase(words[1]) == "list";
    if (list) {
      if (words.size() != 5) fail("'property list' needs a count type, an item type and a name");
      if (!is_integer_type(words[2]) || type_size(words[2]) == 0)
        fail(fmt::format("list count type '{}' is not an integer type", printable_text(words[2], 64)));
      property.count_size = type_size(words[2]);
      property.count_signed = is_signed_type(words[2]);
    } else if (words.size() != 3) {
      fail("'property' needs a type and a name");
    }
    const std::string_view type = list ? words[3] : words[1];
    property.size = type_size(type);
    if (property.size == 0) fail(fmt::format("property '{}' has unknown type '{}'", printable_text(words.back(), 64),
                                                printable_text(type, 64)));
    header.elements.back().properties.push_back(property);
  }

  // `text` holds the start of the file; it must contain the whole header.
  PlyHeader parse(std::string_view text) {
    PlyHeader header;
    std::size_t line_begin = 0;
    for (int line_number = 1;; ++line_number) {
      const std::size_t line_end = text.find('\n', line_begin);
      if (line_end == std::string_view::npos)
        fail(fmt::format("no 'end_header' line in the first {} bytes", std::min(text.size(), kMaxHeaderBytes)));
      const std::vector<std::string_view> words = split_words(text.substr(line_begin, line_end - line_begin));
      line_begin = line_end + 1;
      if (words.empty()) continue;
      const std::string keyword = lowercase(words[0]);
      if (line_number == 1) continue;  // "ply"
      if (keyword == "format")
        parse_format(words, header);
      else if (keyword == "element")
        parse_element(words, header);
      else if (keyword == "property")
        parse_property(words, header);
      else if (keyword == "end_header")
        break;
      // comment, obj_info and other lines carry no sizes
    }
    if (!has_format_) fail("no 'format' line");
    header.data_offset = line_begin;
    return header;
  }

 private:
  const std::string& path_;
  bool has_format_ = false;
};

// The least bytes one element takes in the file.
std::uint64_t least_element_bytes(const PlyElement& element, PlyFormat format) {
  std::uint64_t bytes = 0;
  for (const PlyProperty& p : element.properties)
    bytes += format == PlyFormat::Ascii ? 2 : static_cast<std::uint64_t>(p.count_size > 0 ? p.count_size : p.size);
  return std::max<std::uint64_t>(bytes, 1);  // an element of no properties still counts, as its count is allocated
}

std::string element_list(const PlyHeader& header) {
  std::string list;
  for (const PlyElement& e : header.elements) list += fmt::format("{}{} {}", list.empty() ? "" : ", ", e.count, e.name);
  return list;
}

void check_least_size(const std::string& path, const PlyHeader& header, std::uint64_t data_bytes) {
  std::uint64_t least = 0;
  for (const PlyElement& e : header.elements)
    least = saturating_add(least, saturating_mul(e.count, least_element_bytes(e, header.format)));
  if (header.format == PlyFormat::Ascii && least > 0) --least;  // the last value needs no separator
  if (least <= data_bytes) return;
  throw Error(
      fmt::format("{}: the PLY header declares {} elements, at least {} bytes of {} data, but the file "
                  "holds {} bytes after the header",
                  path, element_list(header), least == kSaturated ? std::string("2^64") : std::to_string(least),
                  header.format == PlyFormat::Ascii ? "ASCII" : "binary", data_bytes));
}

// Sequential reads of the binary data through a buffer, bounded by the file size.
class DataReader {
 public:
  DataReader(std::ifstream& file, std::uint64_t begin, std::uint64_t end) : file_(file), position_(begin), end_(end) {}

  bool skip(std::uint64_t bytes) {
    position_ = saturating_add(position_, bytes);
    return position_ <= end_;
  }

  bool read(void* data, std::size_t size) {
    if (saturating_add(position_, size) > end_) return false;
    if (position_ < buffer_begin_ || position_ + size > buffer_begin_ + buffer_.size()) fill();
    std::memcpy(data, buffer_.data() + (position_ - buffer_begin_), size);
    position_ += size;
    return true;
  }

 private:
  void fill() {
    buffer_.resize(static_cast<std::size_t>(std::min<std::uint64_t>(1 << 20, end_ - position_)));
    file_.clear();
    file_.seekg(static_cast<std::streamoff>(position_));
    file_.read(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_begin_ = position_;
  }

  std::ifstream& file_;
  std::uint64_t position_;
  std::uint64_t end_;
  std::vector<char> buffer_;
  std::uint64_t buffer_begin_ = 0;
};

// A list's length (negative for a negative count of a signed type); nullopt when the file ends first.
std::optional<std::int64_t> read_list_length(DataReader& reader, const PlyProperty& p, PlyFormat format) {
  unsigned char raw[4] = {};
  if (!reader.read(raw, static_cast<std::size_t>(p.count_size))) return std::nullopt;
  if (format == PlyFormat::BinaryBigEndian) std::reverse(raw, raw + p.count_size);
  std::uint64_t value = 0;
  for (int i = p.count_size - 1; i >= 0; --i) value = (value << 8) | raw[i];
  const std::uint64_t sign_bit = std::uint64_t{1} << (8 * p.count_size - 1);
  if (p.count_signed && (value & sign_bit)) return -1;
  return static_cast<std::int64_t>(value);
}

// Walks the binary data element by element, reading each list's length, and throws at the first element that
// ends past the end of the file.
void check_binary_lists(const std::string& path, const PlyHeader& header, std::uint64_t file_size) {
  std::ifstream file(path, std::ios::binary);
  DataReader reader(file, header.data_offset, file_size);
  for (const PlyElement& e : header.elements) {
    const auto truncated = [&](std::uint64_t i) {
      throw Error(fmt::format("{}: the PLY file is truncated: {} {} of {} ends past the end of the file", path, e.name,
                              i, e.count));
    };
    const bool has_lists =
        std::any_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.count_size > 0; });
    if (!has_lists) {
      reader.skip(saturating_mul(e.count, least_element_bytes(e, header.format)));  // within the least size
      continue;
    }
    for (std::uint64_t i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        if (p.count_size == 0) {
          if (!reader.skip(static_cast<std::uint64_t>(p.size))) truncated(i);
          continue;
        }
        const std::optional<std::int64_t> length = read_list_length(reader, p, header.format);
        if (!length) truncated(i);
        if (*length < 0)
          throw Error(fmt::format("{}: PLY {} {} of {} has a negative list length", path, e.name, i, e.count));
        if (!reader.skip(saturating_mul(static_cast<std::uint64_t>(*length), static_cast<std::uint64_t>(p.size))))
          truncated(i);
      }
  }
}

}  // namespace

void check_ply_size(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return;  // the importer reports unreadable files
  std::string start(4, '\0');
  file.read(start.data(), 4);
  const bool is_ply =
      file.gcount() == 4 && lowercase(start.substr(0, 3)) == "ply" && (start[3] == '\n' || start[3] == '\r');
  if (!is_ply) return;
  start.resize(kMaxHeaderBytes);
  file.read(start.data() + 4, static_cast<std::streamsize>(start.size() - 4));
  start.resize(4 + static_cast<std::size_t>(file.gcount()));
  file.clear();
  file.seekg(0, std::ios::end);
  const auto file_size = static_cast<std::uint64_t>(file.tellg());
  const PlyHeader header = HeaderParser(path).parse(start);
  check_least_size(path, header, file_size - header.data_offset);
  if (header.format != PlyFormat::Ascii) check_binary_lists(path, header, file_size);
}

}  // namespace lucent
