// image.h: images in memory and their files (PNG and Radiance HDR through stb, EXR through OpenEXR).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace lucent {

// Linear RGBA, 32-bit float, row-major with the top row first.
struct ImageRGBA32F {
  int width = 0;
  int height = 0;
  std::vector<float> pixels;  // 4 floats per pixel
  float* at(int x, int y) { return &pixels[4 * (static_cast<std::size_t>(y) * width + x)]; }
  const float* at(int x, int y) const { return &pixels[4 * (static_cast<std::size_t>(y) * width + x)]; }
};

// Display-referred RGBA, 8 bits per channel (sRGB encoded), row-major with the top row first.
struct ImageRGBA8 {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // 4 bytes per pixel
  std::uint8_t* at(int x, int y) { return &pixels[4 * (static_cast<std::size_t>(y) * width + x)]; }
  const std::uint8_t* at(int x, int y) const { return &pixels[4 * (static_cast<std::size_t>(y) * width + x)]; }
};

// Each throws lucent::Error naming the path when the file cannot be written or read. Writing replaces the file
// atomically (lucent/output_file.h): a failed write leaves the previous file as it was.
void write_png(const std::string& path, const ImageRGBA8& image);
void write_exr(const std::string& path, const ImageRGBA32F& image);  // RGBA, 32-bit float channels
ImageRGBA8 read_png(const std::string& path);
ImageRGBA32F read_exr(const std::string& path);
// A PNG or JPEG image held in memory (a glTF's embedded image), decoded to RGBA8 with the same size checks as
// read_png. `what` names it in messages: "<what>: cannot read PNG: ...".
ImageRGBA8 decode_image(const std::string& bytes, const std::string& what);
// The width and height a PNG or JPEG held in memory declares in its header, read without decoding it ({0, 0} when
// the bytes are neither); and the same of a PNG, JPEG or HDR file.
std::pair<int, int> encoded_image_size(const std::string& bytes);
std::pair<int, int> image_file_size(const std::string& path);
// Radiance RGBE (.hdr) through stb: RGB with shared 8-bit exponent (about 1% precision, non-negative values);
// alpha is dropped on write and reads as 1.
void write_hdr(const std::string& path, const ImageRGBA32F& image);
ImageRGBA32F read_hdr(const std::string& path);

// The bytes of each format, for writing several files as one set (lucent::OutputSet). Throw lucent::Error.
std::string encode_png(const ImageRGBA8& image);
std::string encode_exr(const ImageRGBA32F& image);
std::string encode_hdr(const ImageRGBA32F& image);

}  // namespace lucent
