// image.cpp: image files. PNG (8-bit RGBA) and Radiance HDR (RGBE) through stb_image / stb_image_write, except
// that .hdr files are read by image/radiance_hdr.cpp; EXR (RGBA, 32-bit float channels, so values round-trip
// exactly) through OpenEXR 3. Readers refuse images over kMaxImagePixels (image/image_limits.h) before
// allocating. Images are encoded in memory and written by write_file (temporary file + rename,
// lucent/output_file.h). Failures throw lucent::Error naming the path.
#include "lucent/image.h"

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include "image/image_limits.h"
#include "io/file_path_check.h"
#include "io/printable_text.h"
#include "image/radiance_hdr.h"
#include "io/input_file.h"
#include "lucent/error.h"
#include "lucent/output_file.h"

// stb is compiled here and only here, with internal linkage so it cannot clash with another copy in the program.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_HDR
#define STBI_ONLY_JPEG
#include <stb/stb_image.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace lucent {
namespace {

constexpr int kChannels = 4;  // RGBA
constexpr const char* kChannelNames[kChannels] = {"R", "G", "B", "A"};

// Number of floats or bytes in an RGBA image of the given size.
std::size_t value_count(int width, int height) {
  return std::size_t{kChannels} * static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
}

// Throws std::invalid_argument unless the image is non-empty and holds exactly width * height RGBA pixels.
template <class Image>
void check_pixel_count(const Image& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw std::invalid_argument(fmt::format("image is {}x{}", image.width, image.height));
  }
  const std::size_t expected = value_count(image.width, image.height);
  if (image.pixels.size() != expected) {
    throw std::invalid_argument(fmt::format("image is {}x{} but holds {} values (expected {})", image.width,
                                            image.height, image.pixels.size(), expected));
  }
}

// One FLOAT slice per RGBA channel over interleaved pixels covering `window`; missing channels read as `fill`.
Imf::FrameBuffer rgba_frame_buffer(const float* pixels, const Imath::Box2i& window, int width) {
  const std::size_t x_stride = sizeof(float) * kChannels;
  const std::size_t y_stride = x_stride * static_cast<std::size_t>(width);
  Imf::FrameBuffer frame_buffer;
  for (int c = 0; c < kChannels; ++c) {
    const double fill = c == 3 ? 1.0 : 0.0;  // opaque when the file has no alpha
    frame_buffer.insert(kChannelNames[c],
                        Imf::Slice::Make(Imf::FLOAT, pixels + c, window, x_stride, y_stride, 1, 1, fill));
  }
  return frame_buffer;
}

// An EXR written into memory, so the file itself is written once, complete, by write_file.
class MemoryStream final : public Imf::OStream {
 public:
  MemoryStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    const std::size_t end = position_ + static_cast<std::size_t>(n);
    if (bytes_.size() < end) bytes_.resize(end);
    std::copy(c, c + n, bytes_.begin() + static_cast<std::ptrdiff_t>(position_));
    position_ = end;
  }
  std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t pos) override { position_ = static_cast<std::size_t>(pos); }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
  std::size_t position_ = 0;
};

std::string exr_bytes(const ImageRGBA32F& image) {
  check_pixel_count(image);
  Imf::Header header(image.width, image.height);
  for (const char* name : kChannelNames) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
  MemoryStream stream;
  {
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(rgba_frame_buffer(image.pixels.data(), header.dataWindow(), image.width));
    file.writePixels(image.height);
  }  // the file's destructor writes the line offset table
  return stream.take();
}

// stb_image_write hands the encoded bytes to this callback, in pieces.
void append_to_string(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

ImageRGBA32F read_exr_pixels(const std::string& path) {
  Imf::InputFile file(path.c_str());
  const Imf::ChannelList& channels = file.header().channels();
  if (!channels.findChannel("R") && !channels.findChannel("G") && !channels.findChannel("B")) {
    throw std::runtime_error("no R, G or B channel");
  }
  const Imath::Box2i window = file.header().dataWindow();
  const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
  const std::int64_t height = std::int64_t{window.max.y} - window.min.y + 1;
  if (const std::string problem = image_size_problem(width, height); !problem.empty())
    throw std::runtime_error(problem);
  std::int64_t data_bytes = 0;  // the pixel data the file declares, every channel at its sampling
  for (auto channel = channels.begin(); channel != channels.end(); ++channel) {
    const Imf::Channel& c = channel.channel();
    const std::int64_t bytes = c.type == Imf::HALF ? 2 : 4;
    const std::int64_t x_sampling = std::max(c.xSampling, 1), y_sampling = std::max(c.ySampling, 1);
    data_bytes += bytes * ((width + x_sampling - 1) / x_sampling) * ((height + y_sampling - 1) / y_sampling);
  }
  std::error_code size_error;
  const auto file_bytes = static_cast<std::int64_t>(std::filesystem::file_size(path, size_error));
  if (const std::string problem = pixel_data_problem(width, height, data_bytes, size_error ? -1 : file_bytes);
      !problem.empty())
    throw std::runtime_error(problem);
  ImageRGBA32F image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.pixels.resize(value_count(image.width, image.height));
  file.setFrameBuffer(rgba_frame_buffer(image.pixels.data(), window, image.width));
  file.readPixels(window.min.y, window.max.y);
  return image;
}

std::int64_t big_endian_32(const unsigned char* bytes) {
  return std::int64_t{bytes[0]} << 24 | std::int64_t{bytes[1]} << 16 | std::int64_t{bytes[2]} << 8 |
         std::int64_t{bytes[3]};
}

// "" when the chunks after the signature are sound up to IEND; else the problem. Every chunk must fit in the file
// (stb_image grows its IDAT buffer from the declared length before reading it, so a 300-byte file declaring a 1 GiB
// chunk would allocate 2 GiB) and the first IDAT must hold data (stb_image copies zero bytes to a null pointer,
// undefined behaviour).
std::string png_chunk_problem(std::istream& file, std::int64_t file_size) {
  unsigned char chunk[8];
  bool seen_idat = false;
  for (std::int64_t offset = 8; file.seekg(offset) && file.read(reinterpret_cast<char*>(chunk), 8);) {
    const std::int64_t length = big_endian_32(chunk);
    const std::string type(reinterpret_cast<const char*>(chunk + 4), 4);
    if (length > file_size - offset - 12)  // length, type, data, CRC
      return fmt::format("the chunk at byte {} declares {} bytes, past the end of the file", offset, length);
    if (type == "IDAT" && !seen_idat) {
      if (length == 0) return "the first IDAT chunk is empty";
      seen_idat = true;
    }
    if (type == "IEND") return "";
    offset += 12 + length;
  }
  return "";  // no IEND: stb_image names the problem
}

// "" when the file starts with the PNG signature, its IHDR chunk declares an image within kMaxImagePixels and its
// chunks are sound (png_chunk_problem); else the problem. Checked before stb_image, which would also decode
// other formats.
std::string png_stream_problem(std::istream& file) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  unsigned char start[26] = {};
  file.read(reinterpret_cast<char*>(start), sizeof start);
  if (file.gcount() < 8 || std::memcmp(start, kSignature, 8) != 0) return "not a PNG file";
  if (file.gcount() < 26 || std::memcmp(start + 12, "IHDR", 4) != 0) return "";  // stb_image names the problem
  const std::int64_t width = big_endian_32(start + 16), height = big_endian_32(start + 20);
  if (std::string problem = image_size_problem(width, height); !problem.empty()) return problem;
  file.clear();
  file.seekg(0, std::ios::end);
  const std::int64_t file_size = file.tellg();
  // The filtered scanlines the image data inflates to: a filter byte and the row's samples (colour type 0 grey,
  // 2 RGB, 3 palette index, 4 grey + alpha, 6 RGBA) at the bit depth.
  static constexpr int kSamples[7] = {1, 0, 3, 1, 2, 0, 4};
  const int samples = start[25] < 7 ? std::max(kSamples[start[25]], 1) : 1;
  const std::int64_t row_bytes = 1 + (width * samples * std::max<int>(start[24], 1) + 7) / 8;
  if (std::string problem = pixel_data_problem(width, height, height * row_bytes, file_size); !problem.empty())
    return problem;
  return png_chunk_problem(file, file_size);
}

std::string png_header_problem(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::strerror(errno);
  return png_stream_problem(file);
}

// The decoded pixels as RGBA8, or the problem stb_image reports.
ImageRGBA8 decoded_rgba8(std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> data, int width, int height,
                         const std::string& what, const char* format) {
  if (!data) {
    const char* reason = stbi_failure_reason();
    throw Error(fmt::format("{}: cannot read {}: {}", what, format, reason ? reason : "corrupt or unsupported image data"));
  }
  ImageRGBA8 image;
  image.width = width;
  image.height = height;
  image.pixels.assign(data.get(), data.get() + value_count(width, height));
  return image;
}

}  // namespace

std::string encode_png(const ImageRGBA8& image) {
  try {
    check_pixel_count(image);
  } catch (const std::exception& e) {
    throw Error(fmt::format("cannot encode PNG: {}", e.what()));
  }
  std::string bytes;
  const int stride = kChannels * image.width;
  if (stbi_write_png_to_func(append_to_string, &bytes, image.width, image.height, kChannels, image.pixels.data(),
                             stride) == 0)
    throw Error("cannot encode PNG");
  return bytes;
}

std::string encode_exr(const ImageRGBA32F& image) {
  try {
    return exr_bytes(image);
  } catch (const std::exception& e) {
    throw Error(fmt::format("cannot encode EXR: {}", e.what()));
  }
}

std::string encode_hdr(const ImageRGBA32F& image) {
  try {
    check_pixel_count(image);
  } catch (const std::exception& e) {
    throw Error(fmt::format("cannot encode HDR: {}", e.what()));
  }
  std::vector<float> rgb(3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  for (std::size_t i = 0; i < rgb.size() / 3; ++i)
    for (std::size_t c = 0; c < 3; ++c) rgb[3 * i + c] = image.pixels[kChannels * i + c];
  std::string bytes;
  if (stbi_write_hdr_to_func(append_to_string, &bytes, image.width, image.height, 3, rgb.data()) == 0)
    throw Error("cannot encode HDR");
  return bytes;
}

namespace {

// Encodes with `encode` and writes `path`; an encoding failure names the path too.
template <class Image, class Encode>
void encode_and_write(const std::string& path, const Image& image, Encode encode) {
  std::string bytes;
  try {
    bytes = encode(image);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", path, e.what()));
  }
  write_file(path, bytes);
}

}  // namespace

void write_png(const std::string& path, const ImageRGBA8& image) { encode_and_write(path, image, encode_png); }
void write_exr(const std::string& path, const ImageRGBA32F& image) { encode_and_write(path, image, encode_exr); }
void write_hdr(const std::string& path, const ImageRGBA32F& image) { encode_and_write(path, image, encode_hdr); }

ImageRGBA8 read_png(const std::string& path) {
  check_file_path(path);
  require_regular_file(path);
  if (const std::string problem = png_header_problem(path); !problem.empty())
    throw Error(fmt::format("{}: cannot read PNG: {}", path, problem));
  int width = 0, height = 0, channels_in_file = 0;
  const std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> data(
      stbi_load(path.c_str(), &width, &height, &channels_in_file, kChannels), &stbi_image_free);
  if (!data) {
    // stb_image leaves the reason unset on some failures (a truncated or corrupt compressed stream).
    const char* reason = stbi_failure_reason();
    throw Error(fmt::format("{}: cannot read PNG: {}", path, reason ? reason : "corrupt or unsupported image data"));
  }
  ImageRGBA8 image;
  image.width = width;
  image.height = height;
  image.pixels.assign(data.get(), data.get() + value_count(width, height));
  return image;
}

std::pair<int, int> encoded_image_size(const std::string& bytes) {
  int width = 0, height = 0, channels = 0;
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
      stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()), &width,
                            &height, &channels) == 0)
    return {0, 0};
  return {width, height};
}

std::pair<int, int> image_file_size(const std::string& path) {
  check_file_path(path);
  require_regular_file(path);
  int width = 0, height = 0, channels = 0;
  if (stbi_info(path.c_str(), &width, &height, &channels) == 0) return {0, 0};
  return {width, height};
}

ImageRGBA8 decode_image(const std::string& bytes, const std::string& what) {
  static constexpr unsigned char kJpegStart[3] = {0xff, 0xd8, 0xff};
  const bool jpeg = bytes.size() >= 3 && std::memcmp(bytes.data(), kJpegStart, 3) == 0;
  const char* format = jpeg ? "JPEG" : "PNG";
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error(fmt::format("{}: cannot read {}: {} bytes, more than stb_image reads", what, format, bytes.size()));
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  if (jpeg) {  // the size a JPEG declares, checked before its pixels are allocated
    int width = 0, height = 0, channels = 0;
    if (stbi_info_from_memory(data, size, &width, &height, &channels) != 0)
      for (const std::string& problem :
           {image_size_problem(width, height),
            pixel_data_problem(width, height, std::int64_t{width} * height * 3, static_cast<std::int64_t>(size))})
        if (!problem.empty()) throw Error(fmt::format("{}: cannot read JPEG: {}", what, problem));
  } else {
    std::istringstream stream(bytes);
    if (const std::string problem = png_stream_problem(stream); !problem.empty())
      throw Error(fmt::format("{}: cannot read PNG: {}", what, problem == "not a PNG file" ? "not a PNG or JPEG image" : problem));
  }
  int width = 0, height = 0, channels_in_file = 0;
  std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> pixels(
      stbi_load_from_memory(data, size, &width, &height, &channels_in_file, kChannels), &stbi_image_free);
  return decoded_rgba8(std::move(pixels), width, height, what, format);
}

ImageRGBA32F read_exr(const std::string& path) {
  check_file_path(path);
  require_regular_file(path);
  try {
    return read_exr_pixels(path);
  } catch (const std::exception& e) {
    throw Error(fmt::format("{}: cannot read EXR: {}", path, printable_text(e.what())));
  }
}

ImageRGBA32F read_hdr(const std::string& path) {
  check_file_path(path);
  require_regular_file(path);
  try {
    return read_radiance_hdr_file(path);
  } catch (const std::exception& e) {
    throw Error(fmt::format("{}: cannot read HDR: {}", path, e.what()));
  }
}

}  // namespace lucent
