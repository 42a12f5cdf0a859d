// test_gltf_file_check.cpp: glTF files that a loader must reject (the specification's list) and files whose sizes
// or URIs would make a reader allocate gigabytes or block forever, refused with one line naming the key, before the
// mesh importer or tinygltf reads them. Each passed silently before (a triangle dropped, 2 GB allocated, a hang).
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../test_support.h"
#include "lucent/error.h"
#include "lucent/image.h"
#include "lucent/mesh.h"
#include "lucent/scene.h"
#include "scene/gltf_reader.h"

namespace lucent {
namespace {

namespace fs = std::filesystem;
using test::error_message;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "lucent_gltf_check" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void put(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// A tetrahedron's buffer: 4 float positions, then 12 uint16 indices (`last` the final one).
std::string tetrahedron_bytes(std::uint16_t last = 3) {
  const float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::uint16_t indices[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, last};
  std::string bytes(reinterpret_cast<const char*>(positions), sizeof(positions));
  bytes.append(reinterpret_cast<const char*>(indices), sizeof(indices));
  return bytes;
}

// The tetrahedron's glTF JSON with `extra` members added at the top level and `accessor_offset` as the index
// accessor's byteOffset.
std::string tetrahedron_json(const std::string& buffer_uri, const std::string& extra = "",
                             const std::string& accessor_offset = "0") {
  return fmt::format(R"({{"asset": {{"version": "2.0"}}, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
    "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1, "material": 0}}]}}],
    "materials": [{{"name": "m"}}],
    "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]}},
                  {{"bufferView": 1, "byteOffset": {}, "componentType": 5123, "count": 12, "type": "SCALAR"}}],
    "bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 24}}],
    "buffers": [{{"uri": "{}", "byteLength": 72}}]{}}})",
                     accessor_offset, buffer_uri, extra);
}

TEST(GltfFileCheck, AValidFileLoads) {
  const fs::path dir = fresh_dir("valid");
  put(dir / "buf.bin", tetrahedron_bytes());
  put(dir / "m.gltf", tetrahedron_json("buf.bin"));
  EXPECT_EQ(load_mesh((dir / "m.gltf").string()).indices.size(), 12u);
}

TEST(GltfFileCheck, WhatTheSpecificationSaysALoaderMustRejectIsRefused) {
  const fs::path dir = fresh_dir("spec");
  put(dir / "buf.bin", tetrahedron_bytes());
  const std::string path = (dir / "m.gltf").string();
  put(path, tetrahedron_json("buf.bin", R"(, "extensionsUsed": ["EXT_meshopt_compression"],
    "extensionsRequired": ["EXT_meshopt_compression"])"));
  EXPECT_EQ(error_message([&] { load_mesh(path); }),
            path + ": /extensionsRequired/0: the file requires 'EXT_meshopt_compression', which lucent does not read "
                   "(a loader must refuse such a file)");
  put(path, tetrahedron_json("buf.bin", "", "-2"));
  EXPECT_EQ(error_message([&] { load_mesh(path); }),
            path + ": /accessors/1/byteOffset: -2 is not a non-negative whole number of bytes");
  std::string bad_mode = tetrahedron_json("buf.bin");
  bad_mode.replace(bad_mode.find("\"indices\": 1,"), 13, "\"indices\": 1, \"mode\": 7,");
  put(path, bad_mode);
  EXPECT_EQ(error_message([&] { load_mesh(path); }),
            path + ": /meshes/0/primitives/0/mode: 7 is not a primitive mode (0 points to 6 triangle fan)");
  put(path, R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "scale": [NaN, 1, 1]}]})");
  EXPECT_NE(error_message([&] { load_mesh(path); }).find(path + ": cannot read glTF: malformed JSON: line 1, column"),
            std::string::npos);
  put(dir / "short.glb", std::string("glTF\x02\0\0\0", 8));
  EXPECT_EQ(error_message([&] { load_mesh((dir / "short.glb").string()); }),
            (dir / "short.glb").string() + ": cannot read glTF: a truncated GLB: 8 bytes, fewer than a header and a "
                                           "chunk's 20");
  put(dir / "buf.bin", tetrahedron_bytes(4));  // past the 4 vertices: the importer dropped the triangle
  put(path, tetrahedron_json("buf.bin"));
  EXPECT_EQ(error_message([&] { load_mesh(path); }),
            path + ": /meshes/0/primitives/0/indices: index 4 (element 11) is past the last of the 4 vertices of its "
                   "POSITION accessor");
}

// KHR_materials_volume without a thickness is thin-walled (thicknessFactor's default is 0): no medium to render.
TEST(GltfFileCheck, AThinWalledVolumeIsNotReadAsAMedium) {
  const fs::path dir = fresh_dir("thin");
  put(dir / "buf.bin", tetrahedron_bytes());
  std::string text = tetrahedron_json("buf.bin");
  const std::string material = R"("materials": [{"name": "m"}])";
  text.replace(text.find(material), material.size(),
               R"("materials": [{"name": "m", "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                  "KHR_materials_volume": {"attenuationDistance": 0.01, "attenuationColor": [0.5, 0.6, 0.7]}}}])");
  put(dir / "m.gltf", text);
  put(dir / "s.json", R"({"objects": [{"mesh": "m.gltf", "material": "from_mesh"}]})");
  const std::string message = error_message([&] { load_scene((dir / "s.json").string()); });
  EXPECT_NE(message.find("/materials/0/extensions/KHR_materials_volume/thicknessFactor: 0 (glTF's default when "
                         "absent): the material is thin-walled"),
            std::string::npos)
      << message;
}

// Sizes that would make a reader allocate what the file does not hold, and URIs that would block it.
TEST(GltfFileCheck, SizesAndUrisAreCheckedBeforeAnythingIsRead) {
  const fs::path dir = fresh_dir("sizes");
  // A 40-byte GLB declaring a 2 GB JSON chunk.
  std::string glb = "glTF";
  const std::uint32_t header[4] = {2, 40, 0x7ffffff0u, 0x4E4F534Au};
  glb.append(reinterpret_cast<const char*>(header), sizeof(header));
  glb.append(20, ' ');
  put(dir / "big.glb", glb);
  EXPECT_EQ(error_message([&] { load_mesh((dir / "big.glb").string()); }),
            (dir / "big.glb").string() + ": cannot read glTF: GLB chunk 0 declares 2147483632 bytes; 20 remain in the file");
  // A buffer file shorter than its byteLength, and a sparse one of 2 GB.
  put(dir / "short.bin", tetrahedron_bytes().substr(0, 40));
  put(dir / "short.gltf", tetrahedron_json("short.bin"));
  EXPECT_EQ(error_message([&] { load_mesh((dir / "short.gltf").string()); }),
            (dir / "short.gltf").string() + ": /buffers/0/byteLength: 72 bytes; 'short.bin' holds 40");
  {
    std::ofstream sparse(dir / "sparse.bin", std::ios::binary);
    sparse << tetrahedron_bytes();
  }
  fs::resize_file(dir / "sparse.bin", std::uintmax_t{1} << 31);
  std::string sparse_json = tetrahedron_json("sparse.bin");
  sparse_json.replace(sparse_json.find("\"byteLength\": 72"), 16, "\"byteLength\": 2147483648");
  put(dir / "sparse.gltf", sparse_json);
  struct stat s {};
  ASSERT_EQ(::stat((dir / "sparse.bin").c_str(), &s), 0);
  if (static_cast<std::uintmax_t>(s.st_blocks) * 512u >= (std::uintmax_t{1} << 28))
    GTEST_SKIP() << "the file system does not keep sparse files";
  const std::string sparse_message = error_message([&] { load_mesh((dir / "sparse.gltf").string()); });
  EXPECT_NE(sparse_message.find("/buffers/0/uri: 'sparse.bin' is a sparse file: 2147483648 bytes long"),
            std::string::npos)
      << sparse_message;
  // A FIFO as a buffer and as an image: refused at once, not opened.
  ASSERT_EQ(::mkfifo((dir / "fifo.bin").c_str(), 0600), 0);
  put(dir / "fifo.gltf", tetrahedron_json("fifo.bin"));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(error_message([&] { load_mesh((dir / "fifo.gltf").string()); }),
            (dir / "fifo.gltf").string() + ": /buffers/0/uri: 'fifo.bin' is a FIFO, not a regular file");
  put(dir / "buf.bin", tetrahedron_bytes());
  put(dir / "fifo_image.gltf", tetrahedron_json("buf.bin", R"(, "images": [{"uri": "fifo.bin"}])"));
  EXPECT_EQ(error_message([&] { read_gltf_file((dir / "fifo_image.gltf").string()); }),
            (dir / "fifo_image.gltf").string() + ": /images/0/uri: 'fifo.bin' is a FIFO, not a regular file");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
}

// A small PNG declaring 8192 x 8192 texels as a base colour texture: refused from its header (a material map has at
// most 4096 on a side), not decoded into 256 MB first. (Past 16384 x 16384 the image reader refuses any PNG.)
TEST(GltfFileCheck, ATextureIsMeasuredFromItsHeaderBeforeItIsDecoded) {
  const fs::path dir = fresh_dir("bomb");
  write_png((dir / "tex.png").string(), ImageRGBA8{2, 2, std::vector<std::uint8_t>(16, 200)});
  std::ifstream in(dir / "tex.png", std::ios::binary);
  std::string png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const unsigned char side[4] = {0x00, 0x00, 0x20, 0x00};  // 8192, big-endian, in IHDR's width and height
  png.replace(16, 4, reinterpret_cast<const char*>(side), 4);
  png.replace(20, 4, reinterpret_cast<const char*>(side), 4);
  put(dir / "tex.png", png);
  EXPECT_EQ(encoded_image_size(png), std::make_pair(8192, 8192));
  put(dir / "buf.bin", tetrahedron_bytes());
  put(dir / "m.gltf", tetrahedron_json("buf.bin", R"(, "images": [{"uri": "tex.png"}], "textures": [{"source": 0}])"));
  const GltfFile file = read_gltf_file((dir / "m.gltf").string());
  EXPECT_EQ(error_message([&] { read_gltf_texture(file, 0, {file.path, "/materials/0"}, "m.gltf#tex"); }),
            (dir / "m.gltf").string() + ": /images/0: image is 8192x8192; a material map may have at most 4096 texels "
                                        "on each side");
}

}  // namespace
}  // namespace lucent
