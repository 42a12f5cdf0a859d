// test_image_io.cpp: PNG and EXR files round-trip exactly (bytes, 32-bit floats), EXR files without alpha read
// as opaque, and unreadable or unwritable paths throw lucent::Error messages that name the path.
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <gtest/gtest.h>

#include "../test_support.h"
#include "lucent/error.h"
#include "lucent/image.h"

namespace lucent {
namespace {

using test::error_message;
using test::TempFile;

bool starts_with(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

const std::string kMissingDir = "/nonexistent-lucent-dir";

ImageRGBA8 byte_pattern(int width, int height) {
  ImageRGBA8 image{width, height, {}};
  image.pixels.resize(4 * static_cast<std::size_t>(width) * height);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = static_cast<std::uint8_t>(i * 37 + 11);
  return image;
}

// Values a half-float file would lose: above 65504, below the half subnormals, and float-only mantissa bits.
ImageRGBA32F float_pattern(int width, int height) {
  const float specials[] = {0.0f, 1.0f, 0.1f, 1.0e-30f, 1.0e-40f, 65505.0f, 3.0e38f, 1.0e6f + 0.5f,
                            -2.75f, 0.333333343f, std::numeric_limits<float>::denorm_min(), 7.0e-8f};
  ImageRGBA32F image{width, height, {}};
  image.pixels.resize(4 * static_cast<std::size_t>(width) * height);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = specials[i % std::size(specials)] * (1.0f + static_cast<float>(i) * 1.0e-3f);
  }
  return image;
}

// Writes a 32-bit float EXR with only the named channels, each pixel value = `value`.
void write_exr_channels(const std::string& path, std::initializer_list<const char*> names, float value) {
  const int width = 3, height = 2;
  std::vector<float> plane(static_cast<std::size_t>(width) * height, value);
  Imf::Header header(width, height);
  Imf::FrameBuffer frame_buffer;
  for (const char* name : names) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    frame_buffer.insert(name, Imf::Slice::Make(Imf::FLOAT, plane.data(), header.dataWindow()));
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(frame_buffer);
  file.writePixels(height);
}

TEST(ImageIo, PngRoundTripsExactBytes) {
  const TempFile file(".png");
  const ImageRGBA8 written = byte_pattern(7, 5);
  write_png(file.path(), written);
  const ImageRGBA8 read = read_png(file.path());
  EXPECT_EQ(read.width, 7);
  EXPECT_EQ(read.height, 5);
  EXPECT_EQ(read.pixels, written.pixels);
}

TEST(ImageIo, ExrRoundTripsExactFloats) {
  const TempFile file(".exr");
  const ImageRGBA32F written = float_pattern(6, 4);
  write_exr(file.path(), written);
  const ImageRGBA32F read = read_exr(file.path());
  ASSERT_EQ(read.width, 6);
  ASSERT_EQ(read.height, 4);
  ASSERT_EQ(read.pixels.size(), written.pixels.size());
  for (std::size_t i = 0; i < written.pixels.size(); ++i) {
    EXPECT_EQ(read.pixels[i], written.pixels[i]) << "value " << i;  // bit-exact, not approximately equal
  }
}

TEST(ImageIo, ExrWithoutAlphaReadsOpaque) {
  const TempFile file(".exr");
  write_exr_channels(file.path(), {"R", "G", "B"}, 0.25f);
  const ImageRGBA32F read = read_exr(file.path());
  ASSERT_EQ(read.pixels.size(), 4u * 3 * 2);
  for (int y = 0; y < read.height; ++y) {
    for (int x = 0; x < read.width; ++x) {
      EXPECT_EQ(read.at(x, y)[0], 0.25f);
      EXPECT_EQ(read.at(x, y)[2], 0.25f);
      EXPECT_EQ(read.at(x, y)[3], 1.0f);
    }
  }
}

TEST(ImageIo, ExrWithoutColourChannelsThrows) {
  const TempFile file(".exr");
  write_exr_channels(file.path(), {"Y"}, 0.5f);
  EXPECT_EQ(error_message([&] { read_exr(file.path()); }),
            file.path() + ": cannot read EXR: no R, G or B channel");
}

TEST(ImageIo, MissingFilesThrowNamingThePath) {
  const std::string png = kMissingDir + "/missing.png";
  const std::string exr = kMissingDir + "/missing.exr";
  const std::string png_error = error_message([&] { read_png(png); });
  const std::string exr_error = error_message([&] { read_exr(exr); });
  EXPECT_TRUE(starts_with(png_error, png + ": cannot read PNG: ")) << png_error;
  EXPECT_TRUE(starts_with(exr_error, exr + ": cannot read EXR: ")) << exr_error;
}

TEST(ImageIo, UnwritablePathsThrowNamingThePath) {
  const std::string png = kMissingDir + "/out.png";
  const std::string exr = kMissingDir + "/out.exr";
  EXPECT_EQ(error_message([&] { write_png(png, byte_pattern(2, 2)); }), png + ": cannot write: No such file or directory");
  EXPECT_EQ(error_message([&] { write_exr(exr, float_pattern(2, 2)); }), exr + ": cannot write: No such file or directory");
  EXPECT_FALSE(std::filesystem::exists(kMissingDir)) << "writing a file does not create folders";
}

TEST(ImageIo, InconsistentImagesAreNotWritten) {
  const TempFile file(".png");
  ImageRGBA8 image = byte_pattern(2, 2);
  image.pixels.pop_back();
  EXPECT_EQ(error_message([&] { write_png(file.path(), image); }),
            file.path() + ": cannot encode PNG: image is 2x2 but holds 15 values (expected 16)");
  EXPECT_EQ(error_message([&] { write_exr(file.path(), ImageRGBA32F{}); }),
            file.path() + ": cannot encode EXR: image is 0x0");
}

}  // namespace
}  // namespace lucent
