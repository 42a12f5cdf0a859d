// gltf_reader.h: glTF 2.0 files (.gltf with external files or data: URIs, .glb) read through tinygltf
// (gltf_tinygltf.h), and their textures decoded into lucent's map images.
//
// tinygltf checks the container, the JSON and the buffers; images stay encoded until a texture is used and are
// decoded by lucent's image reader (PNG or JPEG, with its size checks). Each material's "extensions" and "extras"
// are kept as the file's JSON text (tinygltf's original-JSON option) and read with lucent's JSON reader, so their
// errors name the JSON pointer of the bad value, as every scene error does.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "materials/material_maps.h"
#include "params/param_json.h"
#include "scene/gltf_tinygltf.h"

namespace lucent {

struct GltfFile {
  std::string path;
  tinygltf::Model model;
};

// Throws lucent::Error("<path>: cannot read glTF: <problem>") for a missing or malformed file (container, JSON,
// buffers), and "<path>: <pointer>: nested deeper than 128 levels" before tinygltf sees such JSON (its value
// parser recurses once per level).
GltfFile read_gltf_file(const std::string& path);

// The files a glTF names besides itself: every buffer's and image's URI that is not a data: URI, as written and
// percent-decoded (tinygltf opens the one, assimp the other), resolved against the file's folder, used or not (tinygltf opens them all), in the file's order. Empty for a
// file that cannot be read or parsed (reading it names the problem). Outputs are checked against these.
std::vector<std::string> gltf_referenced_files(const std::string& path);

// An object's "extensions" or "extras" JSON text as tinygltf kept it (empty: {}), parsed by lucent's JSON reader.
nlohmann::json gltf_json(const std::string& text, const JsonLocation& where);

// The image of texture `texture_index` as a colour map: 8-bit sRGB decoded to linear, rows from the bottom (v = 0)
// up, as read_material_map gives them (glTF's texture origin is the image's top left, lucent's texture coordinates
// have glTF's v flipped). `where` locates the textureInfo (messages name "<where>/index"); `file_label` becomes
// MapImage::file. Throws lucent::Error for an index out of range, an image that was not loaded (a missing file) or
// does not decode.
MapImage read_gltf_texture(const GltfFile& file, int texture_index, const JsonLocation& where,
                           const std::string& file_label);

}  // namespace lucent
