// test_hostile_images.cpp: image files made to break the readers: truncated and corrupt Radiance HDR files
// (which made stb_image loop forever), sizes past kMaxImagePixels refused before any pixel is allocated (HDR,
// PNG, EXR), a Radiance file passed off as a PNG, and the commands that read them (lucent envmap, lucent
// compare) failing with one line. Files the fuzzer found are in tests/data/hostile/.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <gtest/gtest.h>

#include "../cli_runner.h"
#include "../test_support.h"
#include "image/radiance_hdr.h"
#include "lucent/environment.h"
#include "lucent/error.h"
#include "lucent/image.h"
#include "../test_paths.h"

namespace lucent {
namespace {

using test::error_message;
using test::TempFile;

std::string read_bytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// A sky map as write_hdr writes it (run-length encoded scanlines: the width is at least 8).
std::string sky_hdr_bytes(const TempFile& file, int width) {
  write_hdr(file.path(), environment_map_to_image(make_sky_environment({.width = width})));
  return read_bytes(file.path());
}

std::size_t header_size(const std::string& hdr) { return hdr.find("+X") + hdr.substr(hdr.find("+X")).find('\n') + 1; }

// ---- Radiance HDR ----------------------------------------------------------------------------------------

TEST(HostileHdr, WrittenMapsStillReadBack) {
  const TempFile file(".hdr");
  const EnvironmentMap sky = make_sky_environment({.width = 64});
  write_hdr(file.path(), environment_map_to_image(sky));
  const ImageRGBA32F read = read_hdr(file.path());
  ASSERT_EQ(read.width, 64);
  ASSERT_EQ(read.height, 32);
  for (int y = 0; y < read.height; ++y)
    for (int x = 0; x < read.width; ++x) {
      const glm::vec3 w = sky.at(x, y);
      const float largest = std::max({w.r, w.g, w.b});
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(read.at(x, y)[c], w[c], largest / 128.0f) << x << ", " << y;
      ASSERT_EQ(read.at(x, y)[3], 1.0f);
    }
}

// stb_image looped forever on a run-length encoded file cut short.
TEST(HostileHdr, TruncatedFileIsAnError) {
  const TempFile file(".hdr");
  const std::string whole = sky_hdr_bytes(file, 256);
  write_bytes(file.path(), whole.substr(0, whole.size() / 2));
  EXPECT_EQ(error_message([&] { read_hdr(file.path()); }),
            file.path() + ": cannot read HDR: file ends inside the pixel data (truncated)");
  // Cut so short that the scanlines cannot fit even at the best compression: refused before decoding.
  write_bytes(file.path(), whole.substr(0, header_size(whole) + 100));
  EXPECT_EQ(error_message([&] { read_hdr(file.path()); }),
            file.path() +
                ": cannot read HDR: image is 256x128 but the pixel data is 100 bytes, fewer than the 3584 "
                "it needs at least (truncated)");
}

TEST(HostileHdr, HugeDeclaredSizeIsRefusedBeforeAllocating) {
  const TempFile file(".hdr");
  write_bytes(file.path(), "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n\x02\x02\x01");
  EXPECT_EQ(error_message([&] { read_hdr(file.path()); }),
            file.path() +
                ": cannot read HDR: image is 100000x100000, more than the 268435456 pixels (16384 x "
                "16384) lucent reads");
  // Within the limit, but the 3 bytes of data cannot hold 8192 scanlines.
  write_bytes(file.path(), "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n\x02\x02\x40");
  EXPECT_EQ(error_message([&] { read_hdr(file.path()); }),
            file.path() +
                ": cannot read HDR: image is 16384x8192 but the pixel data is 3 bytes, fewer than the "
                "8552448 it needs at least (truncated)");
}

TEST(HostileHdr, CorruptRunLengthsAreErrors) {
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n";
  const std::string marker = std::string("\x02\x02\x00\x08", 4);
  const std::string zero_run = header + marker + std::string(40, '\0');  // count 0: stb_image's endless loop
  const std::string long_run = header + marker + "\x89\x01" + std::string(40, '\0');  // a run of 9 in 8 pixels
  const std::string wrong_width = header + std::string("\x02\x02\x00\x09", 4) + std::string(40, '\x01');
  const TempFile file(".hdr");
  const std::pair<std::string, std::string> cases[] = {
      {zero_run, "bad run length 0 in the pixel data"},
      {long_run, "bad run length 9 in the pixel data"},
      {wrong_width, "scanline of 9 pixels in an image 8 pixels wide"},
  };
  for (const auto& [bytes, problem] : cases) {
    write_bytes(file.path(), bytes);
    EXPECT_EQ(error_message([&] { read_hdr(file.path()); }), file.path() + ": cannot read HDR: " + problem);
  }
}

TEST(HostileHdr, MalformedHeadersAreNamed) {
  const TempFile file(".hdr");
  const std::pair<std::string, std::string> cases[] = {
      {"not an image", "not a Radiance HDR file (no #?RADIANCE line)"},
      {"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", "header does not end (no resolution line)"},
      {"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\nabcd",
       "unsupported FORMAT=32-bit_rle_xyze (only 32-bit_rle_rgbe)"},
      {"#?RADIANCE\n\n+Y 1 +X 1\nabcd", "unsupported resolution line '+Y 1 +X 1' (only -Y height +X width)"},
      {"#?RADIANCE\n\n-Y 0 +X 1\n", "bad image size '0' in the resolution line"},
      {"#?RADIANCE\n\n-Y 1 +X -4\n", "bad image size '-4' in the resolution line"},
      {"#?RADIANCE\n\n-Y 1 +X 99999999999999999999\n", "bad image size '99999999999999999999' in the resolution line"},
  };
  for (const auto& [bytes, problem] : cases) {
    write_bytes(file.path(), bytes);
    EXPECT_EQ(error_message([&] { read_hdr(file.path()); }), file.path() + ": cannot read HDR: " + problem) << bytes;
  }
}

// Header text quoted in a message keeps it one printable line: control bytes and stray binary bytes as \xNN,
// well-formed UTF-8 as it is, and a long line cut.
TEST(HostileHdr, QuotedHeaderTextIsPrintable) {
  const TempFile file(".hdr");
  const std::pair<std::string, std::string> cases[] = {
      {"#?RADIANCE\nFORMAT=rgbe\r\x1b[2J\xff\xc3\xa9\n\n-Y 1 +X 1\nabcd",
       "unsupported FORMAT=rgbe\\x0d\\x1b[2J\\xff\xc3\xa9 (only 32-bit_rle_rgbe)"},
      {"#?RADIANCE\n\n-Y \x01\x02 +X 1\n", "bad image size '\\x01\\x02' in the resolution line"},
      {"#?RADIANCE\n\n+Y 1 +X 1 " + std::string(100, '\x7f') + "\n",
       "unsupported resolution line '+Y 1 +X 1 " + [] {
         std::string escaped;
         while (escaped.size() < 54) escaped += "\\x7f";
         return escaped;
       }() + "...' (only -Y height +X width)"},
  };
  for (const auto& [bytes, problem] : cases) {
    write_bytes(file.path(), bytes);
    EXPECT_EQ(error_message([&] { read_hdr(file.path()); }), file.path() + ": cannot read HDR: " + problem);
  }
}

// Flat scanlines (width under 8) and the sizes at the limit.
TEST(HostileHdr, FlatScanlinesAndTheLimit) {
  const std::string pixel("\x80\x40\x20\x81", 4);  // (1, 0.5, 0.25)
  const ImageRGBA32F image =
      decode_radiance_hdr("#?RGBE\n\n-Y 2 +X 3\n" + pixel + pixel + pixel + pixel + pixel + pixel);
  ASSERT_EQ(image.width, 3);
  EXPECT_EQ(image.at(2, 1)[0], 1.0f);
  EXPECT_EQ(image.at(2, 1)[1], 0.5f);
  EXPECT_EQ(image.at(2, 1)[2], 0.25f);
  EXPECT_EQ(error_message([] {
              try {
                decode_radiance_hdr("#?RADIANCE\n\n-Y 16385 +X 16384\n");
              } catch (const std::exception& e) {
                throw Error(e.what());
              }
            }),
            "image is 16384x16385, more than the 268435456 pixels (16384 x 16384) lucent reads");
}

// ---- PNG -------------------------------------------------------------------------------------------------

std::string big_endian32(std::uint32_t value) {
  return {static_cast<char>(value >> 24), static_cast<char>(value >> 16), static_cast<char>(value >> 8),
          static_cast<char>(value)};
}

// A PNG signature and IHDR chunk declaring width x height RGBA, then nothing (stb_image does not check CRCs).
std::string png_header(std::uint32_t width, std::uint32_t height) {
  return std::string("\x89PNG\r\n\x1a\n", 8) + big_endian32(13) + "IHDR" + big_endian32(width) + big_endian32(height) +
         std::string("\x08\x06\x00\x00\x00", 5) + big_endian32(0);
}

TEST(HostilePng, HugeDeclaredSizeIsRefused) {
  const TempFile file(".png");
  write_bytes(file.path(), png_header(100000, 100000));
  EXPECT_EQ(error_message([&] { read_png(file.path()); }),
            file.path() +
                ": cannot read PNG: image is 100000x100000, more than the 268435456 pixels (16384 x "
                "16384) lucent reads");
}

// Within the pixel limit but far more pixel data than the file could inflate to: refused before stb_image
// allocates the 1 GiB image. Scanlines: a filter byte and 4 samples of 8 bits a pixel (RGBA), 16384 rows.
TEST(HostilePng, PixelDataTheFileCannotHoldIsRefused) {
  const TempFile file(".png");
  const std::string bytes = png_header(16384, 16384) + big_endian32(4) + "IDAT" + std::string(8, '\0') +
                            big_endian32(0) + "IEND" + big_endian32(0);
  write_bytes(file.path(), bytes);
  EXPECT_EQ(error_message([&] { read_png(file.path()); }),
            file.path() + ": cannot read PNG: image is 16384x16384, " + std::to_string(16384LL * (1 + 4 * 16384)) +
                " bytes of pixel data, more than a file of " + std::to_string(bytes.size()) +
                " bytes can hold (at most 4096 bytes a file byte)");
}

// stb_image decodes any format it was built with; a Radiance file named .png went through its looping HDR reader.
TEST(HostilePng, OtherFormatsAreNotDecoded) {
  const TempFile hdr(".hdr"), png(".png");  // distinct names: TempFile names files after the test
  const std::string sky = sky_hdr_bytes(hdr, 64);
  write_bytes(png.path(), sky.substr(0, sky.size() / 2));
  EXPECT_EQ(error_message([&] { read_png(png.path()); }), png.path() + ": cannot read PNG: not a PNG file");
}

// A corrupt compressed stream for which stb_image sets no failure reason (found by fuzz_image): one line, where
// formatting the missing reason threw fmt::format_error.
TEST(HostilePng, ACorruptStreamWithoutAReasonIsOneLine) {
  const TempFile file(".png");
  // The corpus file's first byte selects fuzz_image's reader (1: PNG); the PNG follows.
  write_bytes(file.path(), test::read_text(std::filesystem::path(LUCENT_SOURCE_DIR) / "tests/fuzz/corpus/image" /
                                                "png_corrupt_stream_no_reason")
                               .substr(1));
  EXPECT_EQ(error_message([&] { read_png(file.path()); }),
            file.path() + ": cannot read PNG: corrupt or unsupported image data");
}

TEST(HostilePng, TruncatedFileIsAnError) {
  const TempFile file(".png");
  ImageRGBA8 image{64, 64, std::vector<std::uint8_t>(64 * 64 * 4)};
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = static_cast<std::uint8_t>(i * 7919 >> 3);
  write_png(file.path(), image);
  const std::string whole = read_bytes(file.path());
  write_bytes(file.path(), whole.substr(0, whole.size() / 2));
  const std::uint32_t idat_length = static_cast<std::uint32_t>(static_cast<unsigned char>(whole[33])) << 24 |
                                    static_cast<std::uint32_t>(static_cast<unsigned char>(whole[34])) << 16 |
                                    static_cast<std::uint32_t>(static_cast<unsigned char>(whole[35])) << 8 |
                                    static_cast<unsigned char>(whole[36]);
  EXPECT_EQ(error_message([&] { read_png(file.path()); }),
            file.path() + ": cannot read PNG: the chunk at byte 33 declares " + std::to_string(idat_length) +
                " bytes, past the end of the file");
}

// Found by fuzz_image: a 301-byte file whose second IDAT chunk declared about 1 GiB made stb_image grow its data
// buffer to 2 GiB before reading (out of memory under libFuzzer). Chunk lengths are checked against the file size.
TEST(HostilePng, ChunkLongerThanTheFileIsRefused) {
  const TempFile file(".png");
  write_bytes(file.path(), png_header(8, 4) + big_endian32(1u << 30) + "IDATx^c`");
  EXPECT_EQ(error_message([&] { read_png(file.path()); }),
            file.path() + ": cannot read PNG: the chunk at byte 33 declares 1073741824 bytes, past the end of the file");
}

// Found by fuzz_image: an empty first IDAT chunk made stb_image copy zero bytes to a null pointer (undefined
// behaviour, an abort under UBSan).
TEST(HostilePng, EmptyFirstDataChunkIsRefused) {
  const std::string path = std::string(LUCENT_TEST_DATA) + "/hostile/png_empty_first_idat.png";
  EXPECT_EQ(error_message([&] { read_png(path); }), path + ": cannot read PNG: the first IDAT chunk is empty");
}

// ---- EXR -------------------------------------------------------------------------------------------------

// An EXR whose header declares width x height; the pixels are never written.
void write_exr_header(const std::string& path, int width, int height) {
  Imf::Header header(width, height);
  header.channels().insert("R", Imf::Channel(Imf::FLOAT));
  Imf::OutputFile file(path.c_str(), header);
}

TEST(HostileExr, HugeDeclaredSizeIsRefusedBeforeAllocating) {
  const TempFile file(".exr");
  write_exr_header(file.path(), 100000, 100000);
  EXPECT_EQ(error_message([&] { read_exr(file.path()); }),
            file.path() +
                ": cannot read EXR: image is 100000x100000, more than the 268435456 pixels (16384 x "
                "16384) lucent reads");
}

// At the pixel limit, one float channel: 1 GiB of pixel data (4 GiB as RGBA floats) declared by a file that holds
// the header and the chunk offsets only. Refused before the image is allocated.
TEST(HostileExr, PixelDataTheFileCannotHoldIsRefusedBeforeAllocating) {
  const TempFile file(".exr");
  write_exr_header(file.path(), 16384, 16384);
  const std::size_t size = read_bytes(file.path()).size();
  ASSERT_LT(size, std::size_t{1} << 20);
  EXPECT_EQ(error_message([&] { read_exr(file.path()); }),
            file.path() + ": cannot read EXR: image is 16384x16384, 1073741824 bytes of pixel data, more than a file "
                          "of " + std::to_string(size) + " bytes can hold (at most 4096 bytes a file byte)");
}

TEST(HostileExr, TruncatedFileIsAnError) {
  const TempFile file(".exr");
  ImageRGBA32F image{32, 16, std::vector<float>(32 * 16 * 4, 0.5f)};
  write_exr(file.path(), image);
  const std::string whole = read_bytes(file.path());
  write_bytes(file.path(), whole.substr(0, whole.size() / 2));
  const std::string message = error_message([&] { read_exr(file.path()); });
  EXPECT_EQ(message.rfind(file.path() + ": cannot read EXR: ", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// ---- the commands ----------------------------------------------------------------------------------------

TEST(HostileImageCommands, EnvmapLightsFailsOnATruncatedMap) {
  const TempFile file(".hdr");
  const std::string whole = sky_hdr_bytes(file, 256);
  write_bytes(file.path(), whole.substr(0, whole.size() / 2));
  const test::CliResult result = test::run_cli("envmap lights " + file.path() + " -M 8", "timeout 20");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.output,
            "lucent: " + file.path() + ": cannot read HDR: file ends inside the pixel data (truncated)\n");
}

TEST(HostileImageCommands, EnvmapLightsFailsOnAHugeMap) {
  const TempFile file(".exr");
  write_exr_header(file.path(), 100000, 50000);
  const test::CliResult result = test::run_cli("envmap lights " + file.path() + " -M 8", "timeout 20");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.output, "lucent: " + file.path() +
                               ": cannot read EXR: image is 100000x50000, more than the "
                               "268435456 pixels (16384 x 16384) lucent reads\n");
}

TEST(HostileImageCommands, CompareFailsOnHugeAndTruncatedImages) {
  const TempFile good("_good.exr"), huge("_huge.exr"), garbage("_garbage.exr");
  write_exr(good.path(), ImageRGBA32F{4, 4, std::vector<float>(64, 1.0f)});
  write_exr_header(huge.path(), 100000, 100000);
  write_bytes(garbage.path(), read_bytes(good.path()).substr(0, 100));
  test::CliResult result = test::run_cli("compare " + good.path() + " " + huge.path(), "timeout 20");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.output, "lucent: " + huge.path() +
                               ": cannot read EXR: image is 100000x100000, more than the "
                               "268435456 pixels (16384 x 16384) lucent reads\n");
  result = test::run_cli("compare " + garbage.path() + " " + good.path(), "timeout 20");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.output.rfind("lucent: " + garbage.path() + ": cannot read EXR: ", 0), 0u) << result.output;
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
}

}  // namespace
}  // namespace lucent
