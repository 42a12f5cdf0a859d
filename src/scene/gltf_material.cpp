// gltf_material.cpp: see gltf_material.h.
#include "scene/gltf_material.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <system_error>

#include <fmt/format.h>

#include "lucent/error.h"
#include "io/input_file.h"
#include "materials/artist_parameters.h"
#include "materials/model_total_reflectance.h"
#include "params/param_json.h"

namespace lucent {
namespace {

using nlohmann::json;

constexpr std::uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"
constexpr double kMetresToMm = 1000.0;

std::uint32_t read_u32(const std::string& bytes, std::size_t offset) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + offset, sizeof v);  // glTF is little-endian, as lucent's targets
  return v;
}

// The JSON chunk of a binary glTF: 12-byte header (magic, version 2, length), then chunks (length, type, data).
// Reads the header and the chunk only, never the binary buffer behind it.
std::string glb_json_chunk(std::ifstream& file, std::uintmax_t file_size, const std::string& path) {
  std::string header(20, '\0');
  file.read(header.data(), 20);
  if (!file || read_u32(header, 0) != kGlbMagic) throw Error(path + ": not a binary glTF (no 'glTF' header)");
  if (read_u32(header, 4) != 2)
    throw Error(fmt::format("{}: binary glTF version {}; lucent reads version 2", path, read_u32(header, 4)));
  const std::uint64_t chunk_length = read_u32(header, 12);
  if (read_u32(header, 16) != kGlbJsonChunk) throw Error(path + ": binary glTF: the first chunk is not JSON");
  if (20 + chunk_length > file_size)
    throw Error(fmt::format("{}: binary glTF: JSON chunk of {} bytes runs past the end of the file", path, chunk_length));
  std::string chunk(chunk_length, '\0');
  file.read(chunk.data(), static_cast<std::streamsize>(chunk_length));
  if (!file) throw Error(path + ": binary glTF: cannot read the JSON chunk");
  return chunk;
}

// A number at `key` of `object` in [lo, hi], or `fallback` where absent.
double read_number(const json& object, const char* key, double fallback, double lo, double hi,
                   const JsonLocation& where) {
  if (!object.contains(key)) return fallback;
  const json& v = object[key];
  if (!v.is_number()) fail(where.child(key), fmt::format("expected a number, got {}", excerpt(v)));
  const double x = v.get<double>();
  if (!(x >= lo && x <= hi))
    fail(where.child(key), fmt::format("{} is out of range; allowed range [{}, {}]", x, lo, hi));
  return x;
}

// `n` numbers in [0, 1] at `key` (colours), the first three returned; `fallback` where absent.
glm::vec3 read_colour(const json& object, const char* key, std::size_t n, glm::vec3 fallback, const JsonLocation& where) {
  if (!object.contains(key)) return fallback;
  const json& v = object[key];
  const JsonLocation at = where.child(key);
  if (!v.is_array() || v.size() != n) fail(at, fmt::format("expected {} numbers in [0, 1], got {}", n, excerpt(v)));
  glm::vec3 colour(0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    if (!v[i].is_number() || !(v[i].get<double>() >= 0.0 && v[i].get<double>() <= 1.0))
      fail(at.child(i), fmt::format("{} is not a number in [0, 1]", excerpt(v[i])));
    if (i < 3) colour[static_cast<int>(i)] = v[i].get<float>();
  }
  return colour;
}

const json& member_object(const json& object, const char* key, const JsonLocation& where) {
  static const json kEmpty = json::object();
  if (!object.contains(key)) return kEmpty;
  if (!object[key].is_object()) fail(where.child(key), fmt::format("expected an object, got {}", excerpt(object[key])));
  return object[key];
}

// The material indices the mesh primitives name (-1: a primitive without one).
std::set<std::int64_t> used_materials(const json& doc, const JsonLocation& root) {
  std::set<std::int64_t> used;
  if (!doc.contains("meshes") || !doc["meshes"].is_array()) fail(root.child("meshes"), "expected an array of meshes");
  for (std::size_t m = 0; m < doc["meshes"].size(); ++m) {
    const json& mesh = doc["meshes"][m];
    const JsonLocation at = root.child("meshes").child(m);
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
      fail(at, "expected an object with an array of primitives");
    for (std::size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const json& primitive = mesh["primitives"][p];
      if (!primitive.is_object()) fail(at.child("primitives").child(p), "expected an object");
      if (!primitive.contains("material")) {
        used.insert(-1);
        continue;
      }
      if (!primitive["material"].is_number_integer())
        fail(at.child("primitives").child(p).child("material"), "expected a material index");
      used.insert(primitive["material"].get<std::int64_t>());
    }
  }
  return used;
}

void read_volume(const json& ext, const JsonLocation& where, GltfMaterial& m) {
  m.has_volume = true;
  m.thickness_factor = static_cast<float>(read_number(ext, "thicknessFactor", 0.0, 0.0, 1e30, where));
  // Any positive distance: one too long for a float's mean free path is refused as mfp_mm.
  m.attenuation_distance_m = read_number(ext, "attenuationDistance", HUGE_VAL, -HUGE_VAL, HUGE_VAL, where);
  if (!(m.attenuation_distance_m > 0.0))
    fail(where.child("attenuationDistance"),
         fmt::format("{:g} is out of range; allowed range (0, inf) m", m.attenuation_distance_m));
  m.has_attenuation_color = ext.contains("attenuationColor");
  m.attenuation_color = read_colour(ext, "attenuationColor", 3, glm::vec3(1.0f), where);
}

GltfMaterial read_material_object(const json& object, int index, const JsonLocation& where) {
  if (!object.is_object()) fail(where, "expected a material object");
  GltfMaterial m;
  m.index = index;
  m.name = object.contains("name") && object["name"].is_string() ? object["name"].get<std::string>() : "";
  m.base_color = read_colour(member_object(object, "pbrMetallicRoughness", where), "baseColorFactor", 4,
                             glm::vec3(1.0f), where.child("pbrMetallicRoughness"));
  const json& ext = member_object(object, "extensions", where);
  const JsonLocation ext_at = where.child("extensions");
  if (ext.contains("KHR_materials_volume"))
    read_volume(member_object(ext, "KHR_materials_volume", ext_at), ext_at.child("KHR_materials_volume"), m);
  if (ext.contains("KHR_materials_ior"))
    m.ior = static_cast<float>(read_number(member_object(ext, "KHR_materials_ior", ext_at), "ior", 1.5, 1.0, 3.0,
                                           ext_at.child("KHR_materials_ior")));
  if (ext.contains("KHR_materials_diffuse_transmission")) {
    const json& dt = member_object(ext, "KHR_materials_diffuse_transmission", ext_at);
    const JsonLocation dt_at = ext_at.child("KHR_materials_diffuse_transmission");
    m.has_diffuse_transmission = true;
    m.diffuse_transmission_factor = static_cast<float>(read_number(dt, "diffuseTransmissionFactor", 0.0, 0.0, 1.0, dt_at));
    m.diffuse_transmission_color = read_colour(dt, "diffuseTransmissionColorFactor", 3, glm::vec3(1.0f), dt_at);
  }
  const json& extras = member_object(object, "extras", where);
  if (extras.contains("lucent")) m.lucent = member_object(extras, "lucent", where.child("extras"));
  return m;
}

// Per band: mfp = d / -ln(c) (Beer's law: white light turns c after d), d [m] -> mm.
json mean_free_path_mm(const GltfMaterial& m, const JsonLocation& where) {
  const JsonLocation volume = where.child("extensions").child("KHR_materials_volume");
  if (!m.has_volume || !std::isfinite(m.attenuation_distance_m))
    fail(volume.child("attenuationDistance"),
         "missing; a translucent material needs a mean free path (or extras.lucent.mfp_mm)");
  const double d_mm = m.attenuation_distance_m * kMetresToMm;
  if (!m.has_attenuation_color) return json::array({d_mm, d_mm, d_mm});
  json mfp = json::array();
  for (int b = 0; b < 3; ++b) {
    const double c = m.attenuation_color[b];
    if (!(c > 0.0 && c < 1.0))
      fail(volume.child("attenuationColor").child(static_cast<std::size_t>(b)),
           fmt::format("{} is out of range; allowed range (0, 1) (1 is no extinction: no mean free path)", c));
    mfp.push_back(d_mm / -std::log(c));
  }
  return mfp;
}

json surface_albedo(const GltfMaterial& m, const JsonLocation& where) {
  for (int b = 0; b < 3; ++b)
    if (!(m.base_color[b] > 0.0f && m.base_color[b] < 1.0f))
      fail(where.child("pbrMetallicRoughness").child("baseColorFactor").child(static_cast<std::size_t>(b)),
           fmt::format("{} is out of range for a translucent material's surface albedo; allowed range (0, 1)",
                       m.base_color[b]));
  return json::array({m.base_color.x, m.base_color.y, m.base_color.z});
}

json array(glm::vec3 v) { return json::array({v.x, v.y, v.z}); }

}  // namespace

json read_gltf_json(const std::string& path) {
  require_regular_file(path);
  std::ifstream file(path, std::ios::binary);
  std::error_code ec;
  const std::uintmax_t file_size = std::filesystem::file_size(path, ec);
  if (!file || ec) throw Error(path + ": cannot open glTF file");
  std::string magic(4, '\0');
  file.read(magic.data(), 4);
  file.clear();
  file.seekg(0);
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  const bool binary = extension == ".glb" || read_u32(magic, 0) == kGlbMagic;
  const std::string text = binary ? glb_json_chunk(file, file_size, path)
                                  : std::string((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const json doc = parse_json(text, {path, ""});
  require_object(doc, {path, ""});
  return doc;
}

GltfMaterial read_gltf_material(const std::string& path) {
  const json doc = read_gltf_json(path);
  const JsonLocation root{path, ""};
  const std::set<std::int64_t> used = used_materials(doc, root);
  if (used.empty()) fail(root.child("meshes"), "no primitives, so no material");
  if (used.size() > 1) {
    std::string list;
    for (std::int64_t i : used) list += (list.empty() ? "" : ", ") + (i < 0 ? std::string("none") : std::to_string(i));
    fail(root.child("meshes"), fmt::format("the primitives use {} materials ({}); an object takes one", used.size(), list));
  }
  const std::int64_t index = *used.begin();
  if (index < 0) fail(root.child("meshes"), "the primitives name no material");
  const json materials = doc.value("materials", json::array());
  if (!materials.is_array() || index >= static_cast<std::int64_t>(materials.size()))
    fail(root.child("materials"), fmt::format("no material {} (the primitives name it)", index));
  return read_material_object(materials[static_cast<std::size_t>(index)], static_cast<int>(index),
                              root.child("materials").child(static_cast<std::size_t>(index)));
}

json lucent_material_json(const GltfMaterial& m, const std::string& path) {
  const bool translucent = m.has_volume || (m.has_diffuse_transmission && m.diffuse_transmission_factor > 0.0f) ||
                           !m.lucent.is_null();
  if (!translucent) return nullptr;
  const JsonLocation where{path, fmt::format("/materials/{}", m.index)};
  const json extras = m.lucent.is_null() ? json::object() : m.lucent;
  const bool coefficients = extras.contains("preset") || extras.contains("sigma_a") || extras.contains("sigma_s") ||
                            extras.contains("sigma_s_prime");
  json j = {{"eta", m.ior}};
  if (!coefficients) {
    if (!extras.contains("albedo")) j["albedo"] = surface_albedo(m, where);
    if (!extras.contains("mfp_mm")) j["mfp_mm"] = mean_free_path_mm(m, where);
  }
  j.update(extras);
  return j;
}

json gltf_material_json(const Material& material, float thickness) {
  Material curve = material;
  curve.model = inversion_curve_model(material.model);
  const glm::dvec3 total = model_total_reflectance(curve, 0.0).total;
  const glm::vec3 sigma_t = material.sigma_t();
  const double d_mm = 1.0 / std::min({sigma_t.x, sigma_t.y, sigma_t.z});
  json colour = json::array();
  for (int b = 0; b < 3; ++b) colour.push_back(std::exp(-sigma_t[b] * d_mm));
  json base = json::array();
  for (int b = 0; b < 3; ++b) base.push_back(std::min(total[b], 1.0));  // glTF colours are in [0, 1]
  base.push_back(1.0);
  json lucent = {{"sigma_a", array(material.sigma_a)}, {"sigma_s", array(material.sigma_s)}, {"g", array(material.g)},
                 {"eta", material.eta}, {"model", std::string(to_string(material.model))}};
  return {{"name", material.name},
          {"pbrMetallicRoughness", {{"baseColorFactor", base}, {"metallicFactor", 0.0}}},
          {"extensions",
           {{"KHR_materials_volume",
             {{"thicknessFactor", thickness}, {"attenuationDistance", d_mm / kMetresToMm}, {"attenuationColor", colour}}},
            {"KHR_materials_ior", {{"ior", material.eta}}}}},
          {"extras", {{"lucent", lucent}}}};
}

json gltf_opaque_material_json(glm::vec3 albedo) {
  return {{"pbrMetallicRoughness", {{"baseColorFactor", {albedo.x, albedo.y, albedo.z, 1.0f}}, {"metallicFactor", 0.0}}}};
}

}  // namespace lucent
