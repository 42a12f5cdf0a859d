// radiance_hdr.cpp: the bounded Radiance RGBE reader of radiance_hdr.h.
#include "image/radiance_hdr.h"

#include <cerrno>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "image/image_limits.h"
#include "io/printable_text.h"

namespace lucent {
namespace {

constexpr std::size_t kMaxHeaderBytes = 1 << 16;
constexpr int kMinRunLengthWidth = 8, kMaxRunLengthWidth = 0x7fff;  // scanlines outside are always flat
constexpr int kMaxRun = 127;                                        // pixels of one run (count byte 128 + n)
// A file can hold no more than about 4 bytes a pixel (flat), plus the run-length overhead and the header.
constexpr std::uint64_t kMaxFileBytes = 5 * static_cast<std::uint64_t>(kMaxImagePixels) + kMaxHeaderBytes;

[[noreturn]] void fail(const std::string& problem) { throw std::runtime_error(problem); }

class Cursor {
 public:
  explicit Cursor(std::string_view data) : data_(data) {}

  std::size_t left() const { return data_.size() - position_; }
  bool starts_with(std::string_view text) const { return data_.substr(position_).starts_with(text); }

  std::uint8_t byte() {
    if (position_ >= data_.size()) fail("file ends inside the pixel data (truncated)");
    return static_cast<std::uint8_t>(data_[position_++]);
  }

  // The next line without its '\n'; fails when none ends within the header's bound.
  std::string_view line() {
    const std::size_t end = data_.find('\n', position_);
    if (end == std::string_view::npos || end >= kMaxHeaderBytes) fail("header does not end (no resolution line)");
    std::string_view text = data_.substr(position_, end - position_);
    position_ = end + 1;
    return text;
  }

 private:
  std::string_view data_;
  std::size_t position_ = 0;
};

void read_header(Cursor& in) {
  if (!in.starts_with("#?RADIANCE\n") && !in.starts_with("#?RGBE\n"))
    fail("not a Radiance HDR file (no #?RADIANCE line)");
  in.line();
  for (std::string_view line = in.line(); !line.empty(); line = in.line()) {
    if (!line.starts_with("FORMAT=")) continue;  // EXPOSURE, GAMMA, comments: ignored, as by stb_image
    if (line != "FORMAT=32-bit_rle_rgbe")
      fail(fmt::format("unsupported {} (only 32-bit_rle_rgbe)", printable_text(line, 64)));
  }
}

int parse_dimension(std::string_view text) {
  std::int64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [last, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || last != end || value <= 0 || value > kMaxImagePixels)
    fail(fmt::format("bad image size '{}' in the resolution line", printable_text(text, 64)));
  return static_cast<int>(value);
}

// The resolution line "-Y height +X width"; other orientations are not supported.
void read_resolution(Cursor& in, int& width, int& height) {
  const std::string_view line = in.line();
  std::string_view words[4];
  std::size_t count = 0, i = 0;
  while (i < line.size() && count <= 4) {
    const std::size_t begin = line.find_first_not_of(' ', i);
    if (begin == std::string_view::npos) break;
    const std::size_t end = std::min(line.find(' ', begin), line.size());
    if (count < 4) words[count] = line.substr(begin, end - begin);
    ++count;
    i = end;
  }
  if (count != 4 || words[0] != "-Y" || words[2] != "+X")
    fail(fmt::format("unsupported resolution line '{}' (only -Y height +X width)", printable_text(line, 64)));
  height = parse_dimension(words[1]);
  width = parse_dimension(words[3]);
}

bool run_length_possible(int width) { return width >= kMinRunLengthWidth && width <= kMaxRunLengthWidth; }

// The fewest bytes a scanline takes: runs of 127 in each channel, behind a 4-byte marker; else flat.
std::uint64_t least_scanline_bytes(int width) {
  const auto w = static_cast<std::uint64_t>(width);
  return run_length_possible(width) ? 4 + 4 * 2 * ((w + kMaxRun - 1) / kMaxRun) : 4 * w;
}

// One channel of a run-length encoded scanline into rgbe[4 * x + channel].
void read_channel(Cursor& in, std::vector<std::uint8_t>& rgbe, int width, int channel) {
  for (int x = 0; x < width;) {
    int count = in.byte();
    const bool run = count > 128;
    if (run) count -= 128;
    if (count == 0 || count > width - x) fail(fmt::format("bad run length {} in the pixel data", count));
    const std::uint8_t value = run ? in.byte() : 0;
    for (int i = 0; i < count; ++i, ++x) rgbe[4 * static_cast<std::size_t>(x) + channel] = run ? value : in.byte();
  }
}

// A scanline of `width` RGBE pixels into rgbe, flat or run-length encoded (marker 2, 2, width high, width low).
void read_scanline(Cursor& in, std::vector<std::uint8_t>& rgbe, int width) {
  std::uint8_t first[4] = {in.byte(), in.byte(), in.byte(), in.byte()};
  const bool encoded = run_length_possible(width) && first[0] == 2 && first[1] == 2 && (first[2] & 0x80) == 0;
  if (!encoded) {
    std::memcpy(rgbe.data(), first, 4);
    for (std::size_t i = 4; i < 4 * static_cast<std::size_t>(width); ++i) rgbe[i] = in.byte();
    return;
  }
  const int encoded_width = (first[2] << 8) | first[3];
  if (encoded_width != width)
    fail(fmt::format("scanline of {} pixels in an image {} pixels wide", encoded_width, width));
  for (int channel = 0; channel < 4; ++channel) read_channel(in, rgbe, width, channel);
}

void rgbe_to_rgba(const std::uint8_t* rgbe, float* rgba) {
  const float scale = rgbe[3] == 0 ? 0.0f : std::ldexp(1.0f, rgbe[3] - (128 + 8));
  for (int c = 0; c < 3; ++c) rgba[c] = rgbe[c] * scale;
  rgba[3] = 1.0f;
}

}  // namespace

ImageRGBA32F decode_radiance_hdr(std::string_view data) {
  Cursor in(data);
  read_header(in);
  ImageRGBA32F image;
  read_resolution(in, image.width, image.height);
  if (const std::string problem = image_size_problem(image.width, image.height); !problem.empty()) fail(problem);
  const std::uint64_t least = static_cast<std::uint64_t>(image.height) * least_scanline_bytes(image.width);
  if (least > in.left())
    fail(fmt::format("image is {}x{} but the pixel data is {} bytes, fewer than the {} it needs at least (truncated)",
                     image.width, image.height, in.left(), least));

  image.pixels.resize(4 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  std::vector<std::uint8_t> rgbe(4 * static_cast<std::size_t>(image.width));
  for (int y = 0; y < image.height; ++y) {
    read_scanline(in, rgbe, image.width);
    for (int x = 0; x < image.width; ++x) rgbe_to_rgba(&rgbe[4 * static_cast<std::size_t>(x)], image.at(x, y));
  }
  return image;
}

ImageRGBA32F read_radiance_hdr_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) fail(std::strerror(errno));
  const std::streamoff size = file.tellg();
  if (size < 0) fail("cannot tell the file size");
  if (static_cast<std::uint64_t>(size) > kMaxFileBytes)
    fail(fmt::format("file of {} bytes is larger than any picture lucent reads", size));
  std::string data(static_cast<std::size_t>(size), '\0');
  file.seekg(0);
  if (!file.read(data.data(), size)) fail("cannot read the file");
  return decode_radiance_hdr(data);
}

}  // namespace lucent
