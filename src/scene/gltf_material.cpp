// gltf_material.cpp: see gltf_material.h.
#include "scene/gltf_material.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <set>

#include <fmt/format.h>

#include "bssrdf/multipole.h"
#include "io/printable_text.h"
#include "lucent/error.h"
#include "materials/artist_parameters.h"
#include "materials/model_total_reflectance.h"
#include "params/param_json.h"
#include "scene/gltf_reader.h"

namespace lucent {
namespace {

using nlohmann::json;

constexpr double kMetresToMm = 1000.0;
constexpr int kRepeat = 10497, kNearest = 9728, kNearestMipmapNearest = 9984, kNearestMipmapLinear = 9986;
// The extensions the mapping reads; any other material extension is named in the warning.
const std::set<std::string> kReadExtensions = {"KHR_materials_volume", "KHR_materials_ior",
                                               "KHR_materials_diffuse_transmission", "KHR_materials_transmission",
                                               "KHR_materials_volume_scatter"};

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

std::string location(const GltfMaterial& m) { return fmt::format("/materials/{}", m.index); }
JsonLocation material_at(const GltfMaterial& m) { return {m.path, location(m)}; }
JsonLocation extension_at(const GltfMaterial& m, const char* name) {
  return material_at(m).child("extensions").child(name);
}

// The material indices the mesh primitives name (-1: a primitive without one).
std::set<int> used_materials(const tinygltf::Model& model) {
  std::set<int> used;
  for (const tinygltf::Mesh& mesh : model.meshes)
    for (const tinygltf::Primitive& primitive : mesh.primitives) used.insert(primitive.material);
  return used;
}

// Textures inside an extension that lucent reads, named when present.
void note_textures(const json& ext, std::initializer_list<const char*> keys, const char* name, GltfMaterial& m) {
  for (const char* key : keys)
    if (ext.contains(key)) m.ignored.push_back(fmt::format("{}.{}", name, key));
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
  note_textures(ext, {"thicknessTexture"}, "KHR_materials_volume", m);
}

void read_extensions(const json& ext, const JsonLocation& ext_at, GltfMaterial& m) {
  for (const auto& [name, value] : ext.items())
    if (!kReadExtensions.count(name)) m.ignored.push_back(printable_text(name));
  if (ext.contains("KHR_materials_volume"))
    read_volume(member_object(ext, "KHR_materials_volume", ext_at), ext_at.child("KHR_materials_volume"), m);
  if (ext.contains("KHR_materials_ior"))
    m.ior = static_cast<float>(read_number(member_object(ext, "KHR_materials_ior", ext_at), "ior", 1.5, 1.0, 3.0,
                                           ext_at.child("KHR_materials_ior")));
  if (ext.contains("KHR_materials_transmission")) {
    const json& t = member_object(ext, "KHR_materials_transmission", ext_at);
    m.has_transmission = true;
    m.transmission_factor = static_cast<float>(
        read_number(t, "transmissionFactor", 0.0, 0.0, 1.0, ext_at.child("KHR_materials_transmission")));
    note_textures(t, {"transmissionTexture"}, "KHR_materials_transmission", m);
  }
  if (ext.contains("KHR_materials_diffuse_transmission")) {
    const json& dt = member_object(ext, "KHR_materials_diffuse_transmission", ext_at);
    const JsonLocation dt_at = ext_at.child("KHR_materials_diffuse_transmission");
    m.has_diffuse_transmission = true;
    m.diffuse_transmission_factor = static_cast<float>(read_number(dt, "diffuseTransmissionFactor", 0.0, 0.0, 1.0, dt_at));
    m.has_diffuse_transmission_color = dt.contains("diffuseTransmissionColorFactor");
    m.diffuse_transmission_color = read_colour(dt, "diffuseTransmissionColorFactor", 3, glm::vec3(1.0f), dt_at);
    note_textures(dt, {"diffuseTransmissionTexture", "diffuseTransmissionColorTexture"},
                  "KHR_materials_diffuse_transmission", m);
  }
  if (ext.contains("KHR_materials_volume_scatter")) {
    const json& vs = member_object(ext, "KHR_materials_volume_scatter", ext_at);
    const JsonLocation vs_at = ext_at.child("KHR_materials_volume_scatter");
    m.has_volume_scatter = true;
    const char* key = vs.contains("multiscatterColorFactor") ? "multiscatterColorFactor" : "multiscatterColor";
    m.has_multiscatter_color = vs.contains(key);
    m.multiscatter_color = read_colour(vs, key, 3, glm::vec3(0.0f), vs_at);
    m.scatter_anisotropy = static_cast<float>(read_number(vs, "scatterAnisotropy", 0.0, -1.0, 1.0, vs_at));
    if (std::abs(m.scatter_anisotropy) >= 1.0f)
      fail(vs_at.child("scatterAnisotropy"), fmt::format("{} is out of range; lucent's phase functions take (-1, 1)",
                                                         m.scatter_anisotropy));
    note_textures(vs, {"multiscatterColorTexture"}, "KHR_materials_volume_scatter", m);
  }
}

// The sampler's settings lucent's maps do not have (they repeat and filter bilinearly), named.
void note_sampler(const tinygltf::Model& model, int texture, GltfMaterial& m) {
  const int s = model.textures[static_cast<std::size_t>(texture)].sampler;
  if (s < 0 || static_cast<std::size_t>(s) >= model.samplers.size()) return;
  const tinygltf::Sampler& sampler = model.samplers[static_cast<std::size_t>(s)];
  auto wrap = [](int mode) { return mode == 33071 ? "CLAMP_TO_EDGE" : mode == 33648 ? "MIRRORED_REPEAT" : "?"; };
  if (sampler.wrapS != kRepeat) m.ignored.push_back(fmt::format("/samplers/{}/wrapS {} (maps repeat)", s, wrap(sampler.wrapS)));
  if (sampler.wrapT != kRepeat) m.ignored.push_back(fmt::format("/samplers/{}/wrapT {} (maps repeat)", s, wrap(sampler.wrapT)));
  if (sampler.magFilter == kNearest) m.ignored.push_back(fmt::format("/samplers/{}/magFilter NEAREST (maps are bilinear)", s));
  if (sampler.minFilter == kNearest || sampler.minFilter == kNearestMipmapNearest ||
      sampler.minFilter == kNearestMipmapLinear)
    m.ignored.push_back(fmt::format("/samplers/{}/minFilter {} (maps are bilinear)", s, sampler.minFilter));
}

// A whole number >= 0 at `key` (a texture coordinate set).
int read_set(const json& object, const char* key, int fallback, const JsonLocation& where) {
  if (!object.contains(key)) return fallback;
  const json& v = object[key];
  if (!v.is_number_unsigned() || v.get<std::uint64_t>() > 1000000)
    fail(where.child(key), fmt::format("expected a texture coordinate set (a whole number >= 0), got {}", excerpt(v)));
  return static_cast<int>(v.get<std::uint64_t>());
}

// Two finite numbers at `key`, or `fallback` where absent.
glm::dvec2 read_pair(const json& object, const char* key, glm::dvec2 fallback, const JsonLocation& where) {
  if (!object.contains(key)) return fallback;
  const json& v = object[key];
  if (!v.is_array() || v.size() != 2) fail(where.child(key), fmt::format("expected 2 numbers, got {}", excerpt(v)));
  glm::dvec2 pair;
  for (std::size_t i = 0; i < 2; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      fail(where.child(key).child(i), fmt::format("{} is not a finite number", excerpt(v[i])));
    pair[static_cast<int>(i)] = v[i].get<double>();
  }
  return pair;
}

// The sets a mesh loader reads: assimp keeps 8 (AI_MAX_NUMBER_OF_TEXTURECOORDS).
constexpr int kUvSetsRead = 8;

// The set `set` must be an attribute of every primitive (lucent's mesh is all of the file's primitives).
void require_texture_coordinate_set(const tinygltf::Model& model, int set, const JsonLocation& where) {
  if (set >= kUvSetsRead)
    fail(where, fmt::format("{}: lucent reads texture coordinate sets 0 to {}", set, kUvSetsRead - 1));
  const std::string attribute = fmt::format("TEXCOORD_{}", set);
  for (std::size_t m = 0; m < model.meshes.size(); ++m)
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p)
      if (!model.meshes[m].primitives[p].attributes.count(attribute))
        fail(where, fmt::format("{}: /meshes/{}/primitives/{} has no attribute {}", set, m, p, attribute));
}

// textureInfo.texCoord and KHR_texture_transform (its texCoord overrides the textureInfo's).
GltfTextureCoordinates read_texture_coordinates(const tinygltf::Model& model, const tinygltf::TextureInfo& info,
                                                const json& extensions, const JsonLocation& at) {
  GltfTextureCoordinates c;
  if (info.texCoord < 0) fail(at.child("texCoord"), fmt::format("{} is not a texture coordinate set", info.texCoord));
  c.set = info.texCoord;
  JsonLocation set_at = at.child("texCoord");
  if (extensions.contains("KHR_texture_transform")) {
    const JsonLocation t_at = at.child("extensions").child("KHR_texture_transform");
    const json& t = member_object(extensions, "KHR_texture_transform", at.child("extensions"));
    c.transformed = true;
    c.offset = read_pair(t, "offset", glm::dvec2(0.0), t_at);
    c.scale = read_pair(t, "scale", glm::dvec2(1.0), t_at);
    c.rotation = read_number(t, "rotation", 0.0, -HUGE_VAL, HUGE_VAL, t_at);
    if (!std::isfinite(c.rotation)) fail(t_at.child("rotation"), fmt::format("{} is not a finite number", c.rotation));
    if (t.contains("texCoord")) c.set = read_set(t, "texCoord", c.set, t_at), set_at = t_at.child("texCoord");
  }
  if (c.set != 0) require_texture_coordinate_set(model, c.set, set_at);
  return c;
}

void read_base_color_texture(const GltfFile& file, const tinygltf::TextureInfo& info, GltfMaterial& m) {
  const JsonLocation at = material_at(m).child("pbrMetallicRoughness").child("baseColorTexture");
  const json extensions = gltf_json(info.extensions_json_string, at.child("extensions"));
  m.base_color_coordinates = read_texture_coordinates(file.model, info, extensions, at);
  m.base_color_texture_at = at.pointer;
  m.base_color_texture = read_gltf_texture(file, info.index, at, fmt::format("{}#{}/pbrMetallicRoughness/baseColorTexture",
                                                                           m.path, location(m)));
  note_sampler(file.model, info.index, m);
  for (auto it = extensions.begin(); it != extensions.end(); ++it)
    if (it.key() != "KHR_texture_transform") m.ignored.push_back("baseColorTexture." + printable_text(it.key()));
}

// The core fields lucent does not use, named when the file sets them to something lucent does not reproduce.
void note_core_fields(const tinygltf::Material& material, GltfMaterial& m) {
  const tinygltf::PbrMetallicRoughness& pbr = material.pbrMetallicRoughness;
  if (material.values.count("metallicFactor") && pbr.metallicFactor != 0.0)
    m.ignored.push_back(fmt::format("metallicFactor {:g}", pbr.metallicFactor));
  if (material.values.count("roughnessFactor") && pbr.roughnessFactor != 0.0)
    m.ignored.push_back(fmt::format("roughnessFactor {:g} (the boundary is smooth; the methods' specular roughness is "
                                    "a method parameter)", pbr.roughnessFactor));
  if (material.values.count("metallicRoughnessTexture")) m.ignored.push_back("metallicRoughnessTexture");
  if (pbr.baseColorFactor.size() == 4 && pbr.baseColorFactor[3] != 1.0)
    m.ignored.push_back(fmt::format("baseColorFactor alpha {:g}", pbr.baseColorFactor[3]));
  for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture", "alphaCutoff"})
    if (material.additionalValues.count(key)) m.ignored.push_back(key);
  if (std::any_of(material.emissiveFactor.begin(), material.emissiveFactor.end(), [](double e) { return e != 0.0; }))
    m.ignored.push_back("emissiveFactor");
  if (material.alphaMode != "OPAQUE") m.ignored.push_back("alphaMode " + printable_text(material.alphaMode));
  if (material.doubleSided) m.ignored.push_back("doubleSided (objects are closed volumes)");
}

void read_base_color(const tinygltf::Material& material, GltfMaterial& m) {
  const JsonLocation pbr_at = material_at(m).child("pbrMetallicRoughness");
  const std::vector<double>& factor = material.pbrMetallicRoughness.baseColorFactor;
  m.has_base_color_factor = material.values.count("baseColorFactor") > 0;
  if (!m.has_base_color_factor) return;  // glTF's default [1, 1, 1, 1]
  if (factor.size() != 4) fail(pbr_at.child("baseColorFactor"), "expected 4 numbers in [0, 1]");
  for (std::size_t i = 0; i < 4; ++i)
    if (!(factor[i] >= 0.0 && factor[i] <= 1.0))
      fail(pbr_at.child("baseColorFactor").child(i), fmt::format("{:g} is not a number in [0, 1]", factor[i]));
  m.base_color = glm::vec3(static_cast<float>(factor[0]), static_cast<float>(factor[1]), static_cast<float>(factor[2]));
}

// The cube root of |det| of a node's local transform: its scale, for thickness (rotations do not change lengths).
double node_scale(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    const std::vector<double>& a = node.matrix;  // column-major
    const double det = a[0] * (a[5] * a[10] - a[9] * a[6]) - a[4] * (a[1] * a[10] - a[9] * a[2]) +
                       a[8] * (a[1] * a[6] - a[5] * a[2]);
    return std::cbrt(std::abs(det));
  }
  return node.scale.size() == 3 ? std::cbrt(std::abs(node.scale[0] * node.scale[1] * node.scale[2])) : 1.0;
}

// The world scale of the first node that instances a mesh using material `index` (1 where none does).
double mesh_to_world(const tinygltf::Model& model, int index) {
  std::vector<int> parent(model.nodes.size(), -1);
  for (std::size_t n = 0; n < model.nodes.size(); ++n)
    for (int child : model.nodes[n].children)
      if (child >= 0 && static_cast<std::size_t>(child) < parent.size()) parent[static_cast<std::size_t>(child)] = static_cast<int>(n);
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    const int mesh = model.nodes[n].mesh;
    if (mesh < 0 || static_cast<std::size_t>(mesh) >= model.meshes.size()) continue;
    const auto& primitives = model.meshes[static_cast<std::size_t>(mesh)].primitives;
    if (std::none_of(primitives.begin(), primitives.end(), [&](const tinygltf::Primitive& p) { return p.material == index; }))
      continue;
    double scale = 1.0;
    int node = static_cast<int>(n);
    for (std::size_t steps = 0; node >= 0 && steps <= model.nodes.size(); ++steps, node = parent[static_cast<std::size_t>(node)])
      scale *= node_scale(model.nodes[static_cast<std::size_t>(node)]);
    return std::isfinite(scale) && scale > 0.0 ? scale : 1.0;
  }
  return 1.0;
}

GltfMaterial read_material(const GltfFile& file, int index) {
  const tinygltf::Material& material = file.model.materials[static_cast<std::size_t>(index)];
  GltfMaterial m;
  m.path = file.path;
  m.index = index;
  m.name = material.name;
  m.mesh_to_world = mesh_to_world(file.model, index);
  read_base_color(material, m);
  note_core_fields(material, m);
  const JsonLocation at = material_at(m);
  read_extensions(gltf_json(material.extensions_json_string, at.child("extensions")), at.child("extensions"), m);
  const json extras = gltf_json(material.extras_json_string, at.child("extras"));
  if (extras.contains("lucent")) m.lucent = member_object(extras, "lucent", at.child("extras"));
  if (material.pbrMetallicRoughness.baseColorTexture.index >= 0)
    read_base_color_texture(file, material.pbrMetallicRoughness.baseColorTexture, m);
  return m;
}

// ---- the mapping ----

// The medium's colour parameters per band as lucent needs them: the model, g and eta the surface albedo is inverted
// with (extras.lucent's where it names them).
struct CurveParameters {
  BssrdfModel model = kDefaultBssrdfModel;
  glm::vec3 g{0.0f};
  float eta = 1.5f;
};

CurveParameters curve_parameters(const GltfMaterial& m) {
  CurveParameters p;
  p.eta = m.ior;
  p.g = glm::vec3(m.scatter_anisotropy);
  const json& x = m.lucent;
  if (!x.is_object()) return p;
  if (x.contains("model") && x["model"].is_string())
    if (auto model = parse_bssrdf_model(x["model"].get<std::string>())) p.model = *model;
  if (x.contains("eta") && x["eta"].is_number()) p.eta = std::clamp(x["eta"].get<float>(), 1.0f, 3.0f);
  if (x.contains("g") && x["g"].is_number()) p.g = glm::vec3(x["g"].get<float>());
  if (x.contains("g") && x["g"].is_array() && x["g"].size() == 3)
    for (int b = 0; b < 3; ++b)
      if (x["g"][static_cast<std::size_t>(b)].is_number()) p.g[b] = x["g"][static_cast<std::size_t>(b)].get<float>();
  for (int b = 0; b < 3; ++b) p.g[b] = std::clamp(p.g[b], -0.99f, 0.99f);  // out of range: read_material says so
  return p;
}

// T = c^(t / d): what is left of white light after crossing the thickness (1 without a volume, thin-walled, or an
// infinite distance).
glm::vec3 volume_transmittance(const GltfMaterial& m) {
  if (!m.has_volume || !(m.thickness_factor > 0.0f) || !std::isfinite(m.attenuation_distance_m)) return glm::vec3(1.0f);
  const double x = m.thickness_factor * m.mesh_to_world / m.attenuation_distance_m;  // both in world units
  glm::vec3 t;
  for (int b = 0; b < 3; ++b) t[b] = static_cast<float>(std::pow(static_cast<double>(m.attenuation_color[b]), x));
  return t;
}

// A = (1 - s) ((1 - f) B + f D T) + s B T = a B + b, per band: a and b.
void albedo_affine(const GltfMaterial& m, glm::vec3& a, glm::vec3& b) {
  const glm::vec3 T = volume_transmittance(m);
  const float s = m.transmission_factor, f = m.diffuse_transmission_factor;
  a = (1.0f - s) * (1.0f - f) + s * T;
  b = (1.0f - s) * f * m.diffuse_transmission_color * T;
}

// The key whose value makes band `band` of the surface albedo 0.
JsonLocation zero_albedo_key(const GltfMaterial& m, int band) {
  const auto b = static_cast<std::size_t>(band);
  if (m.has_base_color_factor && m.base_color[band] == 0.0f)
    return material_at(m).child("pbrMetallicRoughness").child("baseColorFactor").child(b);
  if (m.base_color_texture) return material_at(m).child("pbrMetallicRoughness").child("baseColorTexture");
  if (m.has_diffuse_transmission_color && m.diffuse_transmission_color[band] == 0.0f)
    return extension_at(m, "KHR_materials_diffuse_transmission").child("diffuseTransmissionColorFactor").child(b);
  return material_at(m);
}

// The extension that makes a material without a volume translucent, for messages.
JsonLocation translucency_key(const GltfMaterial& m) {
  if (m.has_diffuse_transmission && m.diffuse_transmission_factor > 0.0f)
    return extension_at(m, "KHR_materials_diffuse_transmission");
  if (m.has_transmission && m.transmission_factor > 0.0f) return extension_at(m, "KHR_materials_transmission");
  return extension_at(m, "KHR_materials_volume_scatter");
}

// The distance d [mm], or an error at a key that exists when the file gives none.
double attenuation_distance_mm(const GltfMaterial& m) {
  if (!m.has_volume)
    fail(translucency_key(m), "thin-walled (no KHR_materials_volume): lucent renders a medium and needs its "
                              "attenuationDistance, or extras.lucent.mfp_mm");
  if (!(m.thickness_factor > 0.0f))
    fail(extension_at(m, "KHR_materials_volume").child("thicknessFactor"),
         "0 (glTF's default when absent): the material is thin-walled, a surface with no volume behind it; lucent "
         "renders a medium: give the thickness the volume has (in the mesh's units), or extras.lucent.mfp_mm");
  if (!std::isfinite(m.attenuation_distance_m))
    fail(extension_at(m, "KHR_materials_volume"),
         "no attenuationDistance (glTF's default: infinite, a clear medium); lucent's medium needs one, or "
         "extras.lucent.mfp_mm");
  return m.attenuation_distance_m * kMetresToMm;
}

// sigma_t or sigma_a per band from c and d: -ln(c) / d [mm^-1]; c = 1 in a band is refused at its key.
glm::dvec3 log_attenuation(const GltfMaterial& m, double d_mm) {
  glm::dvec3 sigma;
  for (int b = 0; b < 3; ++b) {
    const double c = m.attenuation_color[b];
    if (!(c > 0.0 && c < 1.0))
      fail(extension_at(m, "KHR_materials_volume").child("attenuationColor").child(static_cast<std::size_t>(b)),
           fmt::format("{} is out of range; allowed range (0, 1) (1 is no extinction: no mean free path)", c));
    sigma[b] = -std::log(c) / d_mm;
  }
  return sigma;
}

// Mean free paths [mm] derived from the attenuation, refused at attenuationDistance beyond what a float carries.
glm::dvec3 checked_mfp(const GltfMaterial& m, glm::dvec3 mfp) {
  for (int b = 0; b < 3; ++b)
    if (!(mfp[b] > 1e-30 && mfp[b] < 1e30))
      fail(extension_at(m, "KHR_materials_volume").child("attenuationDistance"),
           fmt::format("{:g} m gives the mean free path {:g} mm in band {}; lucent's range is (1e-30, 1e30) mm",
                       m.attenuation_distance_m, mfp[b], b));
  return mfp;
}

json array(glm::dvec3 v) { return json::array({v.x, v.y, v.z}); }
json array(glm::vec3 v) { return json::array({v.x, v.y, v.z}); }

// KHR_materials_volume_scatter: the medium whole.
json scattering_medium(const GltfMaterial& m, GltfLucentMaterial& out) {
  const double d_mm = attenuation_distance_mm(m);
  const glm::dvec3 sigma_t = m.has_attenuation_color ? log_attenuation(m, d_mm) : glm::dvec3(1.0 / d_mm);
  glm::dvec3 alpha;
  const JsonLocation vs = extension_at(m, "KHR_materials_volume_scatter");
  for (int b = 0; b < 3; ++b) {
    alpha[b] = single_scatter_albedo(m.multiscatter_color[b]);
    if (!(m.multiscatter_color[b] > 0.0f && alpha[b] < 1.0))
      fail(m.has_multiscatter_color ? vs.child("multiscatterColorFactor").child(static_cast<std::size_t>(b)) : vs,
           fmt::format("multi-scatter albedo {} gives the single-scatter albedo {:.6g}; lucent's media scatter and "
                       "absorb (allowed range (0, 1) exclusive){}",
                       m.multiscatter_color[b], alpha[b],
                       m.has_multiscatter_color ? "" : " (absent: glTF's default [0, 0, 0] scatters nothing)"));
  }
  if (m.has_base_color_factor || m.base_color_texture)
    out.ignored.push_back("base colour (with KHR_materials_volume_scatter it tints glTF's boundary; lucent's is a clear "
                          "dielectric and the medium's colour is multiscatterColorFactor's)");
  checked_mfp(m, 1.0 / sigma_t);
  return {{"sigma_a", array(sigma_t * (1.0 - alpha))}, {"sigma_s", array(sigma_t * alpha)},
          {"g", m.scatter_anisotropy}, {"eta", m.ior}};
}

// The surface albedo A per texel (the texture's texels x factor, through A = a B + b) and its mean.
glm::vec3 surface_albedo(const GltfMaterial& m, GltfLucentMaterial& out) {
  glm::vec3 a, b;
  albedo_affine(m, a, b);
  if (!m.base_color_texture) return a * m.base_color + b;
  MapImage map = *m.base_color_texture;
  for (glm::vec3& texel : map.texels) texel = a * (m.base_color * texel) + b;
  const glm::vec3 mean = map_mean(map);
  out.albedo_map = std::move(map);
  return mean;
}

// Volume without scattering given: sigma_a from the attenuation, the scattering that gives the surface albedo.
json absorbing_medium(const GltfMaterial& m, const json& extras, GltfLucentMaterial& out) {
  const glm::vec3 albedo = surface_albedo(m, out);
  const CurveParameters p = curve_parameters(m);
  glm::vec3 reachable;
  glm::dvec3 alpha;
  for (int b = 0; b < 3; ++b) {
    if (!(albedo[b] > 0.0f)) fail(zero_albedo_key(m, b), "makes the surface albedo 0; lucent's media reflect light");
    const AlbedoCurve curve(inversion_curve_model(p.model), p.g[b], p.eta);
    reachable[b] = static_cast<float>(curve.reachable(albedo[b]));
    alpha[b] = curve.alpha(reachable[b]);
  }
  if (reachable != albedo && !out.albedo_map)
    out.clamped.push_back(fmt::format("surface albedo ({:.4g}, {:.4g}, {:.4g}) clamped to ({:.4g}, {:.4g}, {:.4g}), "
                                      "the {} model's range at eta {:.3g}",
                                      albedo.x, albedo.y, albedo.z, reachable.x, reachable.y, reachable.z,
                                      to_string(p.model), p.eta));
  json j = {{"albedo", array(reachable)}, {"eta", m.ior}};
  if (extras.contains("mfp_mm")) return j;
  const double d_mm = attenuation_distance_mm(m);
  if (!m.has_attenuation_color) {
    j["mfp_mm"] = array(checked_mfp(m, glm::dvec3(d_mm)));
    return j;
  }
  const glm::dvec3 sigma_a = log_attenuation(m, d_mm);
  j["mfp_mm"] = array(checked_mfp(m, (1.0 - alpha) / sigma_a));
  return j;
}

// A thin-walled material, KHR_materials_diffuse_transmission without a volume: glTF's surface reflects (1 - f) B
// diffusely and transmits f D. lucent renders it as a sheet of the multipole model (a slab of thickness d whose
// faces are both the surface) whose reflectance and transmittance totals are those, per band: the reduced albedo
// alpha' and optical thickness tau with multipole_beam_totals(alpha', eta, tau) = (R, T); then sigma_t' = tau / d.
constexpr double kDefaultSheetThicknessMm = 0.5;  // a leaf, paper or a lampshade's fabric: tenths of a millimetre
constexpr double kSheetTauMin = 0.25, kSheetTauMax = 64.0;  // the multipole tables' optical thicknesses
constexpr double kSheetAlphaMax = 0.999999;

// The optical thickness with transmittance T at reduced albedo a. The light a sheet scatters through it rises from
// nothing at tau 0 (nothing scattered yet) to a peak and falls: the thicker of the two solutions, on the falling
// side, clamped to the peak when T is more than any thickness transmits and to the tables' range.
glm::vec2 sheet_totals(double a, double eta, double tau) {
  const shader::vec2 t = shader::multipole_beam_totals(static_cast<float>(a), static_cast<float>(eta), static_cast<float>(tau));
  return {t.x, t.y};
}

double sheet_tau(double a, double eta, double T) {
  constexpr int kScan = 48;
  double peak = kSheetTauMin, peak_T = -1.0;
  for (int i = 0; i < kScan; ++i) {
    const double tau = kSheetTauMin * std::pow(kSheetTauMax / kSheetTauMin, i / (kScan - 1.0));
    if (const double t = sheet_totals(a, eta, tau).y; t > peak_T) peak = tau, peak_T = t;
  }
  if (T >= peak_T) return peak;
  double lo = peak, hi = kSheetTauMax;
  for (int i = 0; i < 40; ++i) {
    const double mid = std::sqrt(lo * hi);  // geometric: tau spans decades
    (sheet_totals(a, eta, mid).y > T ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

json thin_sheet(const GltfMaterial& m, const json& extras, GltfLucentMaterial& out) {
  double d_mm = kDefaultSheetThicknessMm;
  if (extras.contains("thickness_mm")) {
    const json& t = extras["thickness_mm"];
    if (!t.is_number() || !(t.get<double>() > 0.0 && t.get<double>() <= 1e6))
      fail(material_at(m).child("extras").child("lucent").child("thickness_mm"),
           fmt::format("{}: the sheet's thickness in mm, a number in (0, 1e6]", excerpt(t)));
    d_mm = t.get<double>();
  } else {
    out.notes.push_back(fmt::format("thin-walled (KHR_materials_diffuse_transmission without KHR_materials_volume): "
                                    "rendered as a sheet {:g} mm thick; extras.lucent.thickness_mm sets it",
                                    d_mm));
  }
  if (m.has_volume) out.ignored.push_back("KHR_materials_volume (thicknessFactor 0: thin-walled)");
  glm::vec3 base = m.base_color;
  if (m.base_color_texture) {
    base *= map_mean(*m.base_color_texture);
    out.ignored.push_back("baseColorTexture (a thin-walled sheet is one medium: the texture's mean times the factor)");
  }
  const double f = m.diffuse_transmission_factor, eta = m.ior;
  glm::dvec3 sigma_a, sigma_s_prime;
  for (int b = 0; b < 3; ++b) {
    const double R = (1.0 - f) * base[b], T = f * m.diffuse_transmission_color[b];
    if (!(T > 0.0)) fail(zero_albedo_key(m, b), "makes the sheet's transmittance 0 in a band; a sheet needs both");
    if (!(R > 0.0)) fail(zero_albedo_key(m, b), "makes the sheet's reflectance 0 in a band; lucent's media reflect light");
    // Along the curve of alpha' that keeps T, R rises with alpha' (less absorbed, more reflected): bisection.
    double lo = 0.0, hi = kSheetAlphaMax;
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (lo + hi);
      (sheet_totals(mid, eta, sheet_tau(mid, eta, T)).x < R ? lo : hi) = mid;
    }
    const double alpha = 0.5 * (lo + hi), tau = sheet_tau(alpha, eta, T);
    const glm::vec2 got = sheet_totals(alpha, eta, tau);
    if (std::abs(got.x - R) > 0.01 || std::abs(got.y - T) > 0.01)
      out.clamped.push_back(fmt::format("band {}: the sheet's reflectance and transmittance ({:.3f}, {:.3f}) moved to "
                                        "({:.3f}, {:.3f}), the nearest a {:g} mm multipole sheet at eta {:.3g} gives "
                                        "(optical thickness {:g} to {:g})",
                                        b, R, T, got.x, got.y, d_mm, eta, kSheetTauMin, kSheetTauMax));
    const double sigma_t = tau / d_mm;
    sigma_s_prime[b] = alpha * sigma_t;
    sigma_a[b] = (1.0 - alpha) * sigma_t;
  }
  out.sheet_thickness_mm = d_mm;
  return {{"sigma_a", array(sigma_a)}, {"sigma_s_prime", array(sigma_s_prime)}, {"eta", eta},
          {"model", "multipole"}, {"thickness_mm", d_mm}};
}

bool thin_walled_diffuse(const GltfMaterial& m, const json& extras) {
  return m.has_diffuse_transmission && m.diffuse_transmission_factor > 0.0f && !(m.transmission_factor > 0.0f) &&
         !m.has_volume_scatter && !(m.has_volume && m.thickness_factor > 0.0f) && !extras.contains("mfp_mm");
}

// extras.lucent.albedo_map "baseColorTexture" (lucent's export of a textured material): the surface albedo per
// texel is the base colour itself (factor x texel), the medium extras.lucent's (mfp_mm, g, eta, model); the glTF
// extensions are for other tools.
json textured_lucent_medium(const GltfMaterial& m, const json& extras, GltfLucentMaterial& out) {
  const JsonLocation at = material_at(m).child("extras").child("lucent");
  if (extras["albedo_map"] != "baseColorTexture")
    fail(at.child("albedo_map"), fmt::format("{}: in a glTF material albedo_map can only be \"baseColorTexture\" (the "
                                             "material's base colour texture is the surface albedo)",
                                             excerpt(extras["albedo_map"])));
  if (!m.base_color_texture) fail(at.child("albedo_map"), "the material has no baseColorTexture");
  if (!extras.contains("mfp_mm")) fail(at, "albedo_map needs mfp_mm, the mean free path the map's albedos scatter at");
  MapImage map = *m.base_color_texture;
  for (glm::vec3& texel : map.texels) texel *= m.base_color;
  const glm::vec3 mean = map_mean(map);
  const CurveParameters p = curve_parameters(m);
  glm::vec3 reachable;
  for (int b = 0; b < 3; ++b) {
    if (!(mean[b] > 0.0f)) fail(zero_albedo_key(m, b), "makes the surface albedo 0; lucent's media reflect light");
    reachable[b] = static_cast<float>(AlbedoCurve(inversion_curve_model(p.model), p.g[b], p.eta).reachable(mean[b]));
  }
  out.albedo_map = std::move(map);
  json j = extras;
  j.erase("albedo_map");
  j["albedo"] = array(reachable);
  if (!j.contains("eta")) j["eta"] = m.ior;
  return j;
}

}  // namespace

double single_scatter_albedo(double multiscatter) {
  const double r = multiscatter;
  const double s = 4.09712 + 4.20863 * r - std::sqrt(9.59217 + 41.6808 * r + 17.7126 * r * r);
  return 1.0 - s * s;
}

double multiscatter_albedo(double single_scatter) {
  double lo = 0.0, hi = 1.0;  // single_scatter_albedo rises on [0, 1]
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (single_scatter_albedo(mid) < single_scatter ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

GltfMaterial read_gltf_material(const std::string& path) {
  const GltfFile file = read_gltf_file(path);
  const JsonLocation root{path, ""};
  const std::set<int> used = used_materials(file.model);
  if (used.empty()) fail(root.child("meshes"), "no primitives, so no material");
  if (used.size() > 1) {
    std::string list;
    for (int i : used) list += (list.empty() ? "" : ", ") + (i < 0 ? std::string("none") : std::to_string(i));
    fail(root.child("meshes"), fmt::format("the primitives use {} materials ({}); an object takes one", used.size(), list));
  }
  const int index = *used.begin();
  if (index < 0) fail(root.child("meshes"), "the primitives name no material");
  if (static_cast<std::size_t>(index) >= file.model.materials.size())
    fail(root.child("materials"), fmt::format("no material {} (the primitives name it)", index));
  return read_material(file, index);
}

GltfLucentMaterial lucent_material(const GltfMaterial& m) {
  GltfLucentMaterial out;
  out.ignored = m.ignored;
  const bool translucent = m.has_volume || m.diffuse_transmission_factor > 0.0f || m.transmission_factor > 0.0f ||
                           m.has_volume_scatter || !m.lucent.is_null();
  if (!translucent) {
    out.opaque_albedo = m.base_color * (m.base_color_texture ? map_mean(*m.base_color_texture) : glm::vec3(1.0f));
    if (m.base_color_texture)
      out.ignored.push_back("baseColorTexture (an opaque object has one albedo: the texture's mean times the factor)");
    return out;
  }
  const json extras = m.lucent.is_null() ? json::object() : m.lucent;
  const bool coefficients = extras.contains("preset") || extras.contains("sigma_a") || extras.contains("sigma_s") ||
                            extras.contains("sigma_s_prime");
  if (extras.contains("albedo_map")) {
    out.material = textured_lucent_medium(m, extras, out);
    return out;
  }
  if (coefficients) {
    out.material = {{"eta", m.ior}};
    if (m.base_color_texture) out.ignored.push_back("baseColorTexture (extras.lucent gives the coefficients)");
  } else if (thin_walled_diffuse(m, extras)) {
    out.material = thin_sheet(m, extras, out);
    json rest = extras;
    rest.erase("thickness_mm");  // the sheet's, already in the material
    if (rest.contains("model") && rest["model"] != "multipole")
      out.ignored.push_back(fmt::format("extras.lucent.model {} (a thin-walled sheet is the multipole model's)",
                                        excerpt(rest["model"])));
    rest.erase("model");
    out.material.update(rest);
    return out;
  } else if (m.has_volume_scatter) {
    out.material = scattering_medium(m, out);
  } else {
    out.material = absorbing_medium(m, extras, out);
  }
  out.material.update(extras);
  return out;
}

glm::dvec2 GltfTextureCoordinates::gltf(glm::dvec2 st) const {
  const double c = std::cos(rotation), s = std::sin(rotation);
  const glm::dvec2 scaled = scale * st;
  return {c * scaled.x + s * scaled.y + offset.x, -s * scaled.x + c * scaled.y + offset.y};
}

glm::dvec2 GltfTextureCoordinates::lucent(glm::vec2 uv) const {
  const glm::dvec2 st = gltf({static_cast<double>(uv.x), 1.0 - static_cast<double>(uv.y)});
  return {st.x, 1.0 - st.y};
}

void transform_texture_coordinates(const GltfMaterial& m, std::vector<glm::vec2>& uvs) {
  const GltfTextureCoordinates& c = m.base_color_coordinates;
  if (!c.transformed) return;
  for (std::size_t i = 0; i < uvs.size(); ++i) {
    const glm::dvec2 uv = c.lucent(uvs[i]);
    if (!(std::abs(uv.x) <= FLT_MAX && std::abs(uv.y) <= FLT_MAX))
      fail({m.path, m.base_color_texture_at + "/extensions/KHR_texture_transform"},
           fmt::format("turns vertex {}'s texture coordinates ({:g}, {:g}) into ({:g}, {:g}), beyond a float", i,
                       uvs[i].x, 1.0f - uvs[i].y, uv.x, 1.0 - uv.y));
    uvs[i] = glm::vec2(uv);
  }
}

std::string ignored_fields_warning(const GltfMaterial& m, const std::vector<std::string>& ignored) {
  if (ignored.empty()) return "";
  std::string list;
  for (const std::string& field : ignored) list += (list.empty() ? "" : ", ") + field;
  return fmt::format("{}: /materials/{}{}: lucent does not use {}", m.path, m.index,
                     m.name.empty() ? "" : fmt::format(" ('{}')", text_excerpt(m.name)), list);
}

json gltf_material_json(const Material& material, float thickness, float roughness) {
  Material curve = material;
  curve.model = inversion_curve_model(material.model);
  const glm::dvec3 total = model_total_reflectance(curve, 0.0).total;
  const glm::vec3 sigma_t = material.sigma_t();
  const double d_mm = 1.0 / std::min({sigma_t.x, sigma_t.y, sigma_t.z});
  json colour = json::array(), base = json::array(), multiscatter = json::array();
  for (int b = 0; b < 3; ++b) {
    colour.push_back(std::exp(-static_cast<double>(sigma_t[b]) * d_mm));
    base.push_back(std::min(total[b], 1.0));  // glTF colours are in [0, 1]
    multiscatter.push_back(multiscatter_albedo(static_cast<double>(material.sigma_s[b]) / sigma_t[b]));
  }
  base.push_back(1.0);
  const double g = (material.g.x + material.g.y + material.g.z) / 3.0;  // glTF has one phase function
  json lucent = {{"sigma_a", array(material.sigma_a)}, {"sigma_s", array(material.sigma_s)}, {"g", array(material.g)},
                 {"eta", material.eta}, {"model", std::string(to_string(material.model))}};
  if (material.thickness_mm > 0.0f) lucent["thickness_mm"] = material.thickness_mm;
  return {{"name", material.name},
          {"pbrMetallicRoughness", {{"baseColorFactor", base}, {"metallicFactor", 0.0}, {"roughnessFactor", roughness}}},
          {"extensions",
           {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
            {"KHR_materials_volume",
             {{"thicknessFactor", thickness}, {"attenuationDistance", d_mm / kMetresToMm}, {"attenuationColor", colour}}},
            {"KHR_materials_volume_scatter", {{"multiscatterColorFactor", multiscatter}, {"scatterAnisotropy", g}}},
            {"KHR_materials_ior", {{"ior", material.eta}}}}},
          {"extras", {{"lucent", lucent}}}};
}

json gltf_opaque_material_json(glm::vec3 albedo, float roughness) {
  return {{"pbrMetallicRoughness", {{"baseColorFactor", {albedo.x, albedo.y, albedo.z, 1.0f}}, {"metallicFactor", 0.0},
                                    {"roughnessFactor", roughness}}}};
}

std::vector<std::string> gltf_material_extensions(const json& material) {
  std::vector<std::string> used;
  if (material.contains("extensions"))
    for (const auto& [name, value] : material["extensions"].items()) used.push_back(name);
  return used;
}

}  // namespace lucent
