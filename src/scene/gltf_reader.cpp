// gltf_reader.cpp: see gltf_reader.h.
#include "scene/gltf_reader.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "io/input_file.h"
#include "io/printable_text.h"
#include "lucent/error.h"
#include "lucent/image.h"
#include "scene/gltf_file_check.h"
#include "shared/tonemap.h"

namespace lucent {
namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"

// The first line of tinygltf's messages (they may hold several), printable.
std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return printable_text(line.empty() ? std::string("unknown problem") : line);
}

// The deepest nesting of arrays and objects in JSON text (brackets outside strings).
std::size_t json_depth(std::string_view text) {
  std::size_t depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

// The JSON text of a .gltf, or of a .glb's first chunk ("" when the container is too short to hold one:
// tinygltf then names the problem).
std::string_view json_text(std::string_view bytes) {
  std::uint32_t magic = 0, length = 0;
  if (bytes.size() < 20) return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0 ? "" : bytes;
  std::memcpy(&magic, bytes.data(), 4);
  if (magic != kGlbMagic) return bytes;
  std::memcpy(&length, bytes.data() + 12, 4);
  return bytes.substr(20, std::min<std::size_t>(length, bytes.size() - 20));
}

// tinygltf's image callback: keep the encoded bytes (decoded when a texture is used).
bool keep_encoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                  int size, void*) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

}  // namespace

GltfFile read_gltf_file(const std::string& path) {
  require_regular_file(path);
  check_gltf_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read glTF: cannot open the file");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (json_depth(json_text(bytes)) > kMaxJsonDepth)
    throw Error(fmt::format("{}: cannot read glTF: JSON nested deeper than {} levels", path, kMaxJsonDepth));
  GltfFile file{path, {}};
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_encoded, nullptr);
  loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
  std::string err, warn;
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const auto size = static_cast<unsigned int>(std::min<std::size_t>(bytes.size(), UINT32_MAX));
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  const bool ok = binary ? loader.LoadBinaryFromMemory(&file.model, &err, &warn, data, size, base_dir)
                         : loader.LoadASCIIFromString(&file.model, &err, &warn, bytes.data(), size, base_dir);
  if (!ok) throw Error(fmt::format("{}: cannot read glTF: {}", path, first_line(err)));
  return file;
}

std::vector<std::string> gltf_referenced_files(const std::string& path) {
  std::vector<std::string> files;
  std::ifstream in(path, std::ios::binary);
  if (!in) return files;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string_view text = json_text(bytes);
  if (json_depth(text) > kMaxJsonDepth) return files;
  const nlohmann::json json = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!json.is_object()) return files;
  // tinygltf decodes %XX escapes before opening the file, assimp does not: both names are inputs.
  auto decoded = [](const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
      if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
          std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
        out.push_back(static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16)));
        i += 2;
      } else {
        out.push_back(uri[i]);
      }
    }
    return out;
  };
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  for (const char* key : {"buffers", "images"}) {
    const auto list = json.find(key);
    if (list == json.end() || !list->is_array()) continue;
    for (const nlohmann::json& entry : *list) {
      if (!entry.is_object()) continue;
      const auto uri = entry.find("uri");
      if (uri == entry.end() || !uri->is_string()) continue;
      const std::string& text_uri = uri->get_ref<const std::string&>();
      if (text_uri.empty() || text_uri.rfind("data:", 0) == 0) continue;
      files.push_back((folder / text_uri).string());
      if (const std::string name = decoded(text_uri); name != text_uri) files.push_back((folder / name).string());
    }
  }
  return files;
}

nlohmann::json gltf_json(const std::string& text, const JsonLocation& where) {
  if (text.empty()) return nlohmann::json::object();
  nlohmann::json value = parse_json(text, where);
  require_object(value, where);
  return value;
}

MapImage read_gltf_texture(const GltfFile& file, int texture_index, const JsonLocation& where,
                           const std::string& file_label) {
  const tinygltf::Model& model = file.model;
  if (texture_index < 0 || static_cast<std::size_t>(texture_index) >= model.textures.size())
    fail(where.child("index"), fmt::format("no texture {} (the file has {})", texture_index, model.textures.size()));
  const int source = model.textures[static_cast<std::size_t>(texture_index)].source;
  const JsonLocation texture_at{file.path, fmt::format("/textures/{}", texture_index)};
  if (source < 0 || static_cast<std::size_t>(source) >= model.images.size())
    fail(texture_at.child("source"), "no PNG or JPEG image (a texture extension's image is not read)");
  const tinygltf::Image& image = model.images[static_cast<std::size_t>(source)];
  const JsonLocation image_at{file.path, fmt::format("/images/{}", source)};
  if (image.image.empty())
    fail(image.uri.empty() ? image_at : image_at.child("uri"),
         image.uri.empty() ? std::string("no image data") : fmt::format("cannot load '{}'", text_excerpt(image.uri)));
  const std::string bytes(image.image.begin(), image.image.end());
  // The size the header declares, before the pixels are decoded (a small file can declare gigabytes of them).
  if (const auto [width, height] = encoded_image_size(bytes); width > kMaxMaterialMapSide || height > kMaxMaterialMapSide)
    fail(image_at, fmt::format("image is {}x{}; a material map may have at most {} texels on each side", width, height,
                               kMaxMaterialMapSide));
  const ImageRGBA8 decoded = decode_image(bytes, image_at.str());
  if (decoded.width > kMaxMaterialMapSide || decoded.height > kMaxMaterialMapSide)
    fail(image_at, fmt::format("image is {}x{}; a material map may have at most {} texels on each side", decoded.width,
                               decoded.height, kMaxMaterialMapSide));
  MapImage map;
  map.file = file_label;
  map.size = {decoded.width, decoded.height};
  map.texels.resize(static_cast<std::size_t>(decoded.width) * static_cast<std::size_t>(decoded.height));
  for (int y = 0; y < decoded.height; ++y)
    for (int x = 0; x < decoded.width; ++x) {
      const std::uint8_t* p = decoded.at(x, decoded.height - 1 - y);  // files store the top row first
      glm::vec3& texel = map.texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(decoded.width) + static_cast<std::size_t>(x)];
      for (int c = 0; c < 3; ++c) texel[c] = shader::srgb_decode(static_cast<float>(p[c]) / 255.0f);
    }
  return map;
}

}  // namespace lucent
