// gltf_scene_export.cpp: a whole scene as one glTF 2.0 file for other tools (lucent/scene_writer.h,
// save_scene_gltf; docs/materials.md, "Whole-scene export"). Written with nlohmann's JSON, as the per-object meshes
// are (scene_writer.cpp); tests read it back through tinygltf.
//
//   node "<scene stem>" (scale scale_mm / 1000: glTF's unit is the metre)
//     one node and mesh per object, named after it, its transform as a matrix, its material (gltf_material.h);
//     an albedo map as the material's baseColorTexture, a PNG (in the buffer of a .glb, beside a .gltf)
//   node "camera": a perspective camera (yfov, the render's aspect ratio)
//   one node per light: KHR_lights_punctual; radiance [W/m^2] -> lux and intensity [W/sr] -> candela at 683 lm/W
#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "io/base64.h"
#include "lucent/error.h"
#include "lucent/image.h"
#include "lucent/output_file.h"
#include "lucent/scene_writer.h"
#include "lucent/warning.h"
#include "materials/artist_parameters.h"
#include "materials/material_maps.h"
#include "scene/gltf_material.h"
#include "shared/tonemap.h"

namespace lucent {
namespace {

using nlohmann::json;

constexpr double kLumensPerWatt = 683.0;  // the photometric convention of glTF's exporters and importers (Blender's)
constexpr float kRoughnessWithoutMethodSpecular = 0.05f;  // nearly smooth; 0 hides point highlights in rasterizers
constexpr int kFloat = 5126, kUnsignedInt = 5125, kArrayBuffer = 34962, kElementArrayBuffer = 34963;

json vec(glm::vec3 v) { return json::array({v.x, v.y, v.z}); }
json matrix(const glm::mat4& m) {
  json j = json::array();
  const float* p = glm::value_ptr(m);  // column-major, as glTF's matrix
  for (int i = 0; i < 16; ++i) j.push_back(p[i]);
  return j;
}

// One binary buffer, its views and accessors.
class BufferBuilder {
 public:
  template <class T>
  int add(const std::vector<T>& values, int component_type, const char* type, int target, json extra = json::object()) {
    while (bytes_.size() % 4 != 0) bytes_.push_back(0);
    const auto* begin = reinterpret_cast<const std::uint8_t*>(values.data());
    views_.push_back({{"buffer", 0}, {"byteOffset", bytes_.size()}, {"byteLength", values.size() * sizeof(T)},
                      {"target", target}});
    bytes_.insert(bytes_.end(), begin, begin + values.size() * sizeof(T));
    json accessor = {{"bufferView", views_.size() - 1}, {"componentType", component_type}, {"count", values.size()},
                     {"type", type}};
    accessor.update(extra);
    accessors_.push_back(accessor);
    return static_cast<int>(accessors_.size()) - 1;
  }
  // A view of raw bytes (an embedded image): its index.
  int add_view(const std::string& bytes) {
    while (bytes_.size() % 4 != 0) bytes_.push_back(0);
    views_.push_back({{"buffer", 0}, {"byteOffset", bytes_.size()}, {"byteLength", bytes.size()}});
    bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
    return static_cast<int>(views_.size()) - 1;
  }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  const json& views() const { return views_; }
  const json& accessors() const { return accessors_; }

 private:
  std::vector<std::uint8_t> bytes_;
  json views_ = json::array(), accessors_ = json::array();
};


json primitive(const TriangleMesh& mesh, BufferBuilder& buffer) {
  glm::vec3 lo(HUGE_VALF), hi(-HUGE_VALF);
  for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  json attributes = {{"POSITION", buffer.add(mesh.positions, kFloat, "VEC3", kArrayBuffer, {{"min", vec(lo)}, {"max", vec(hi)}})},
                     {"NORMAL", buffer.add(mesh.normals, kFloat, "VEC3", kArrayBuffer)}};
  if (!mesh.map_uvs().empty()) {  // glTF's texture origin is the image's top left, lucent's the bottom left
    std::vector<glm::vec2> texcoords;
    for (glm::vec2 uv : mesh.map_uvs()) texcoords.emplace_back(uv.x, 1.0f - uv.y);
    attributes["TEXCOORD_0"] = buffer.add(texcoords, kFloat, "VEC2", kArrayBuffer);
  }
  return {{"attributes", attributes}, {"indices", buffer.add(mesh.indices, kUnsignedInt, "SCALAR", kElementArrayBuffer)},
          {"mode", 4}};
}

// glTF's roughness: the methods' GGX alpha is roughness^2 (glTF's convention), else nearly smooth.
float scene_roughness(const Scene& scene) {
  if (!scene.method_params.has("roughness")) return kRoughnessWithoutMethodSpecular;
  return static_cast<float>(std::sqrt(std::max(scene.method_params.number("roughness"), 0.0)));
}

// The textures of a scene: the albedo maps as PNG images (one per map, however many objects share it).
struct Textures {
  bool binary = false;                   // .glb: images in the buffer; .gltf: files beside it
  std::filesystem::path folder;          // the .gltf's folder
  std::string stem;
  std::vector<const MaterialMaps*> maps;  // image i is maps[i]'s albedo
  json images = json::array(), textures = json::array();
  std::vector<std::pair<std::string, std::string>> files;  // .gltf: (path, PNG bytes)
};

// The file name of image `index` beside a .gltf named `stem`.
std::string image_file_name(const std::string& stem, std::size_t index) {
  return fmt::format("{}_albedo_{}.png", stem, index);
}

// A relative URI for a file name: bytes outside RFC 3986's unreserved characters percent-encoded.
std::string uri_of(const std::string& name) {
  std::string uri;
  for (unsigned char c : name) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~') uri += static_cast<char>(c);
    else uri += fmt::format("%{:02X}", c);
  }
  return uri;
}

// The albedo a map's alpha texels render (the flat total of the inversion curve they were made with, the same
// curve the import inverts), 8-bit sRGB, top row first as image files and glTF's texture origin have it.
ImageRGBA8 albedo_image(const MaterialMaps& maps) {
  const BssrdfModel model = inversion_curve_model(maps.made_with_model);
  std::vector<AlbedoCurve> curves;
  for (int c = 0; c < 3; ++c) curves.emplace_back(model, maps.made_with_g[c], maps.made_with_eta);
  ImageRGBA8 image;
  image.width = maps.alpha_size.x, image.height = maps.alpha_size.y;
  image.pixels.assign(4 * maps.alpha.size(), 255);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3 alpha = maps.alpha[static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x)];
      std::uint8_t* p = image.at(x, image.height - 1 - y);  // the maps' rows run from v = 0 up
      for (int c = 0; c < 3; ++c) {
        const auto albedo = static_cast<float>(std::clamp(curves[static_cast<std::size_t>(c)].total(alpha[c]), 0.0, 1.0));
        p[c] = static_cast<std::uint8_t>(std::lround(shader::srgb_encode(albedo) * 255.0f));
      }
    }
  return image;
}

// The texture index of a material's albedo map, its image added once.
int albedo_texture(const MaterialMaps& maps, Textures& textures, BufferBuilder& buffer) {
  const auto known = std::find(textures.maps.begin(), textures.maps.end(), &maps);
  if (known != textures.maps.end()) return static_cast<int>(known - textures.maps.begin());
  const std::size_t index = textures.maps.size();
  const std::string png = encode_png(albedo_image(maps));
  json image = json::object();
  if (textures.binary) {
    image["bufferView"] = buffer.add_view(png);
    image["mimeType"] = "image/png";
  } else {
    const std::string name = image_file_name(textures.stem, index);
    image["uri"] = uri_of(name);
    textures.files.emplace_back((textures.folder / name).string(), png);
  }
  textures.maps.push_back(&maps);
  textures.images.push_back(image);
  textures.textures.push_back({{"source", index}});  // no sampler: glTF's default repeats, as lucent's maps do
  return static_cast<int>(index);
}

json object_material(const SceneObject& object, float roughness, const std::string& path, Textures& textures,
                     BufferBuilder& buffer) {
  if (!object.material) {
    json m = gltf_opaque_material_json(object.albedo, roughness);
    m["name"] = object.name;
    return m;
  }
  glm::vec3 lo(HUGE_VALF), hi(-HUGE_VALF);
  for (const glm::vec3& p : object.mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 size = glm::max(hi - lo, glm::vec3(0.0f));
  json material = gltf_material_json(*object.material, std::min({size.x, size.y, size.z}), roughness);
  const MaterialMaps* maps = object.material->maps.get();
  if (!maps) return material;
  if (!maps->mfp_mm.empty())
    warn(fmt::format("{}: object '{}': its mfp_map is not written (glTF has no texture for the mean free path; the "
                     "glTF material holds the map's mean; the scene file keeps the map)", path, object.name));
  if (maps->alpha.empty()) return material;
  // The albedo map as the base colour texture; extras.lucent as the scene file's textured material (the mean free
  // path and what the texels were inverted with), which lucent's import reads back with the texture.
  json& pbr = material["pbrMetallicRoughness"];
  pbr["baseColorFactor"] = json::array({1.0, 1.0, 1.0, 1.0});
  pbr["baseColorTexture"] = {{"index", albedo_texture(*maps, textures, buffer)}};
  json& lucent = material["extras"]["lucent"];
  lucent.erase("sigma_a"), lucent.erase("sigma_s");
  const glm::vec3 mfp = maps->base_mfp_mm, g = maps->made_with_g;
  lucent["albedo_map"] = "baseColorTexture";
  lucent["mfp_mm"] = json::array({mfp.x, mfp.y, mfp.z});
  lucent["g"] = json::array({g.x, g.y, g.z});
  lucent["eta"] = maps->made_with_eta;
  lucent["model"] = std::string(to_string(maps->made_with_model));
  return material;
}

// A node whose local -z axis is `direction` (lights), at `position`.
glm::mat4 light_frame(glm::vec3 direction, glm::vec3 position) {
  const glm::vec3 z = -glm::normalize(direction);
  const glm::vec3 helper = std::abs(z.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 x = glm::normalize(glm::cross(helper, z)), y = glm::cross(z, x);
  return glm::mat4(glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(z, 0), glm::vec4(position, 1));
}

// KHR_lights_punctual's colour (normalized to its largest band) and intensity (the largest band, photometric).
json punctual(glm::vec3 watts, const char* type) {
  const float peak = std::max({watts.x, watts.y, watts.z});
  return {{"type", type}, {"color", vec(peak > 0.0f ? watts / peak : glm::vec3(1.0f))},
          {"intensity", kLumensPerWatt * static_cast<double>(peak)}};
}

void add_lights(const Scene& scene, float metres_per_unit, json& doc) {
  json lights = json::array();
  auto node = [&](json light, const glm::mat4& frame, const std::string& name) {
    light["name"] = name;
    lights.push_back(light);
    doc["nodes"].push_back({{"name", name}, {"matrix", matrix(frame)},
                            {"extensions", {{"KHR_lights_punctual", {{"light", lights.size() - 1}}}}}});
    doc["scenes"][0]["nodes"].push_back(doc["nodes"].size() - 1);
  };
  for (std::size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].specular)  // not one of an environment map's lights
      node(punctual(scene.lights[i].radiance, "directional"), light_frame(scene.lights[i].direction, glm::vec3(0.0f)),
           fmt::format("directional light {}", i));
  for (std::size_t i = 0; i < scene.point_lights.size(); ++i) {
    const PointLight& p = scene.point_lights[i];
    json light = punctual(p.intensity, p.spot ? "spot" : "point");
    if (p.spot)
      light["spot"] = {{"innerConeAngle", glm::radians(p.inner_deg)}, {"outerConeAngle", glm::radians(p.outer_deg)}};
    const glm::dvec3 position = (glm::dvec3(p.position) + scene.origin) * static_cast<double>(metres_per_unit);
    node(light, light_frame(p.spot ? p.direction : glm::vec3(0, 0, -1), glm::vec3(position)),
         fmt::format("{} light {}", p.spot ? "spot" : "point", i));
  }
  if (lights.empty()) return;
  doc["extensions"]["KHR_lights_punctual"] = {{"lights", lights}};
  doc["extensionsUsed"].push_back("KHR_lights_punctual");
}

void add_camera(const Scene& scene, float metres_per_unit, json& doc) {
  const Camera& c = scene.camera;
  const double m = metres_per_unit;  // in the file's coordinates (Scene::origin added back), in double
  const glm::mat4 world_from_camera = glm::mat4(glm::inverse(glm::lookAt(
      (glm::dvec3(c.eye) + scene.origin) * m, (glm::dvec3(c.target) + scene.origin) * m, glm::dvec3(c.up))));
  const double distance = glm::length(c.target - c.eye) * static_cast<double>(metres_per_unit);
  doc["cameras"] = json::array({{{"name", "camera"}, {"type", "perspective"},
                                 {"perspective", {{"yfov", glm::radians(static_cast<double>(c.fov_y_deg))},
                                                  {"aspectRatio", static_cast<double>(scene.render.width) / scene.render.height},
                                                  {"znear", 1e-3 * distance}}}}});
  doc["nodes"].push_back({{"name", "camera"}, {"camera", 0}, {"matrix", matrix(world_from_camera)}});
  doc["scenes"][0]["nodes"].push_back(doc["nodes"].size() - 1);
}

// The objects under one node that scales scene units to metres.
void add_objects(const Scene& frozen, const std::string& name, const std::string& path, BufferBuilder& buffer,
                 Textures& textures, json& doc) {
  const float roughness = scene_roughness(frozen);
  // The file's coordinates (Scene::origin added back), then metres.
  const glm::dvec3 origin_m = frozen.origin * (static_cast<double>(frozen.scale_mm) / 1000.0);
  json root = {{"name", name}, {"scale", vec(glm::vec3(frozen.scale_mm / 1000.0f))}, {"children", json::array()},
               {"extras", {{"lucent", {{"scale_mm", frozen.scale_mm}}}}}};
  std::vector<std::string> extensions;
  for (const SceneObject& object : frozen.objects) {
    const json material = object_material(object, roughness, path, textures, buffer);
    for (const std::string& e : gltf_material_extensions(material))
      if (std::find(extensions.begin(), extensions.end(), e) == extensions.end()) extensions.push_back(e);
    doc["materials"].push_back(material);
    doc["meshes"].push_back({{"name", object.name}, {"primitives", json::array({primitive(object.mesh, buffer)})}});
    doc["meshes"].back()["primitives"][0]["material"] = doc["materials"].size() - 1;
    doc["nodes"].push_back({{"name", object.name}, {"mesh", doc["meshes"].size() - 1},
                            {"matrix", matrix(object.world_from_object)}});
    root["children"].push_back(doc["nodes"].size() - 1);
  }
  if (frozen.origin != glm::dvec3(0.0)) root["translation"] = json::array({origin_m.x, origin_m.y, origin_m.z});
  doc["nodes"].push_back(root);
  doc["scenes"][0]["nodes"].push_back(doc["nodes"].size() - 1);
  for (const std::string& e : extensions) doc["extensionsUsed"].push_back(e);
}

std::string padded(std::string chunk, char pad) {
  while (chunk.size() % 4 != 0) chunk += pad;
  return chunk;
}

std::string u32(std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }

// The .glb container: header, JSON chunk, BIN chunk.
std::string glb(const json& doc, const std::vector<std::uint8_t>& bytes) {
  const std::string text = padded(doc.dump(), ' ');
  const std::string bin = padded(std::string(bytes.begin(), bytes.end()), '\0');
  const auto total = static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size());
  return "glTF" + u32(2) + u32(total) + u32(static_cast<std::uint32_t>(text.size())) + "JSON" + text +
         u32(static_cast<std::uint32_t>(bin.size())) + "BIN" + std::string(1, '\0') + bin;
}

}  // namespace

namespace {

// The file's bytes and, for a .gltf, its image files.
struct GltfExport {
  std::string bytes;
  std::vector<std::pair<std::string, std::string>> images;
};

GltfExport export_gltf(const Scene& scene, const std::string& path) {
  static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");
  const bool binary = lowercase_extension(path) == ".glb";
  const Scene frozen = scene_at_time(scene, 0.0);  // deformations applied, blob surfaces extracted
  json doc = {{"asset", {{"version", "2.0"}, {"generator", "lucent save_scene_gltf"}}},
              {"scene", 0},
              {"scenes", json::array({{{"name", std::filesystem::path(path).stem().string()}, {"nodes", json::array()}}})},
              {"nodes", json::array()}, {"meshes", json::array()}, {"materials", json::array()},
              {"extensionsUsed", json::array()}};
  BufferBuilder buffer;
  Textures textures;
  textures.binary = binary;
  textures.folder = std::filesystem::path(path).parent_path();
  textures.stem = std::filesystem::path(path).stem().string();
  const float metres_per_unit = scene.scale_mm / 1000.0f;
  add_objects(frozen, std::filesystem::path(path).stem().string(), path, buffer, textures, doc);
  add_camera(frozen, metres_per_unit, doc);
  add_lights(frozen, metres_per_unit, doc);
  if (doc["extensionsUsed"].empty()) doc.erase("extensionsUsed");
  if (!textures.images.empty()) doc["images"] = textures.images, doc["textures"] = textures.textures;
  doc["bufferViews"] = buffer.views();
  doc["accessors"] = buffer.accessors();
  json buffer_json = {{"byteLength", buffer.bytes().size()}};
  if (!binary) buffer_json["uri"] = "data:application/octet-stream;base64," + base64(buffer.bytes());
  doc["buffers"] = json::array({buffer_json});
  return {binary ? glb(doc, buffer.bytes()) : doc.dump() + "\n", std::move(textures.files)};
}

}  // namespace

std::string scene_gltf(const Scene& scene, const std::string& path) { return export_gltf(scene, path).bytes; }

void save_scene_gltf(const Scene& scene, const std::string& path) {
  std::vector<OutputPath> outputs = {{path, "glTF scene", {".gltf", ".glb"}}};
  // A .gltf's images: one per distinct albedo map, named before anything is written so that the checks see them.
  if (lowercase_extension(path) == ".gltf") {
    std::vector<const MaterialMaps*> maps;
    for (const SceneObject& object : scene.objects)
      if (object.material && object.material->maps && !object.material->maps->alpha.empty() &&
          std::find(maps.begin(), maps.end(), object.material->maps.get()) == maps.end())
        maps.push_back(object.material->maps.get());
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    for (std::size_t i = 0; i < maps.size(); ++i)
      outputs.push_back({(folder / image_file_name(std::filesystem::path(path).stem().string(), i)).string(),
                         "glTF scene's image", {".png"}});
  }
  check_outputs(outputs, scene_input_files(scene));
  const OutputLock lock(outputs);
  GltfExport exported = export_gltf(scene, path);
  OutputSet set;
  set.add(path, std::move(exported.bytes));
  for (auto& [file, bytes] : exported.images) set.add(file, std::move(bytes));
  set.commit();
}

void save_scene_as(const Scene& scene, const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension == ".gltf" || extension == ".glb") save_scene_gltf(scene, path);
  else if (extension == ".json") save_scene(scene, path);
  else throw Error(fmt::format("{}: a scene is saved as .gltf or .glb (one glTF file) or .json (a scene file and its "
                               "meshes)", path));
}

}  // namespace lucent
