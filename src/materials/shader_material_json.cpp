// shader_material_json.cpp: see shader_material_json.h.
#include "materials/shader_material_json.h"

#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "lucent/error.h"
#include "materials/openpbr_subsurface.h"
#include "materials/principled_subsurface.h"

namespace lucent {
namespace {

using nlohmann::json;

// Blender's Principled BSDF inputs that shape its subsurface, with Blender's defaults: Blender 3.4's (subsurface,
// subsurface_color; version 3) or Blender 4's Principled v2 (subsurface_weight, subsurface_scale, ior; version 4).
// The other keys are shared; subsurface_method's random_walk means a different radius in each version.
constexpr ParamDecl kPrincipled[] = {
    {"version", ParamType::Int, "", "", 3, 4, "", "Blender's major version: 3 (Blender 3.4's inputs) or 4 (Principled v2); without it, the version whose own keys the block holds, else 3"},
    {"base_color", ParamType::Vec3, "[0.8, 0.8, 0.8]", "", 0, 1, "", "Base Color (linear RGB); version 3: mixed with subsurface_color by subsurface; version 4: the subsurface albedo"},
    {"subsurface", ParamType::Float, "1", "", 0, 1, "", "version 3: Subsurface weight; scales the radius and mixes the colours"},
    {"subsurface_color", ParamType::Vec3, "[0.8, 0.8, 0.8]", "", 0, 1, "", "version 3: Subsurface Color (linear RGB)"},
    {"subsurface_weight", ParamType::Float, "1", "", 0, 1, "", "version 4: Subsurface Weight (lucent renders 1; 0 is an opaque object)"},
    {"subsurface_radius", ParamType::Vec3, "[1, 0.2, 0.1]", "units", 0, 1e30, "", "Subsurface Radius per band (scene units, times scale_mm; version 4: times subsurface_scale)"},
    {"subsurface_scale", ParamType::Float, "0.05", "units", 0, 1e30, "", "version 4: Subsurface Scale (scene units), multiplies subsurface_radius"},
    {"ior", ParamType::Float, "1.5", "", 0, 1000, "", "version 4: IOR; bends the subsurface entry under random_walk, no effect on the medium"},
    {"subsurface_ior", ParamType::Float, "1.4", "", 1, 3.8, "", "Subsurface IOR: sets the radius (version 3: random_walk; version 4: random_walk_skin); the medium is index-matched (eta 1), as in Cycles"},
    {"subsurface_anisotropy", ParamType::Float, "0", "", 0, 1, "", "Subsurface Anisotropy: Henyey-Greenstein g (clamped to 0.9, as Cycles does)"},
    {"subsurface_method", ParamType::Enum, "\"random_walk\"", "", 0, 0, "random_walk|random_walk_fixed_radius|random_walk_skin|burley",
     "Cycles subsurface method; version 3: random_walk (radius from the colour) or random_walk_fixed_radius; version 4: random_walk (radius as given) or random_walk_skin (radius from the colour); burley has no medium and is refused"},
};
// OpenPBR Surface's subsurface inputs (subsurface_weight defaults to 1 here: the block asks for subsurface).
constexpr ParamDecl kOpenPbr[] = {
    {"subsurface_weight", ParamType::Float, "1", "", 0, 1, "", "mix weight of the subsurface slab (lucent renders 1 only)"},
    {"subsurface_color", ParamType::Vec3, "[0.8, 0.8, 0.8]", "", 0, 1, "", "multiple-scattering albedo C (linear RGB): lucent's albedo"},
    {"subsurface_radius", ParamType::Float, "1", "units", 0, 1e30, "", "length scale of the mean free path (scene units, times scale_mm)"},
    {"subsurface_radius_scale", ParamType::Vec3, "[1, 0.5, 0.25]", "", 0, 1e30, "", "per-band multiplier of subsurface_radius: mfp = radius * scale"},
    {"subsurface_scatter_anisotropy", ParamType::Float, "0", "", -1, 1, "", "Henyey-Greenstein g"},
    {"specular_ior", ParamType::Float, "1.5", "", 1, 3, "", "IOR of the dielectric interface: lucent's eta"},
};
constexpr ParamDecl kOuter[] = {
    {"model", ParamType::Enum, "\"standard\"", "", 0, 0, "standard|directional|photon-beam|better-dipole|tabulated|multipole", "diffusion model S_d"},
    {"thickness_mm", ParamType::Float, "0", "mm", 0, 1e30, "", "the thickness of the part, for the multipole model's reflectance; 0: a half-space"},
    {"thickness_from_mesh", ParamType::Bool, "false", "", 0, 1, "", "the multipole model's thickness measured on the object's mesh per surface point (the scene loader does it: its shape diameter)"},
    {"name", ParamType::String, "\"\"", "", 0, 0, "", "name used in messages"},
};

// A number where a colour is expected sets all three bands.
json normalized(const json& block, std::span<const ParamDecl> params) {
  json copy = block;
  for (const ParamDecl& p : params)
    if (p.type == ParamType::Vec3 && copy.is_object() && copy.contains(p.name) && copy[std::string(p.name)].is_number())
      copy[std::string(p.name)] = json::array({copy[std::string(p.name)], copy[std::string(p.name)], copy[std::string(p.name)]});
  return copy;
}

// The keys (and method names) that only one of Blender 3.4's and Blender 4's Principled BSDF has.
std::vector<std::string> version_keys(const json& block, int version) {
  static const std::vector<std::string> kV3Keys{"subsurface", "subsurface_color"};
  static const std::vector<std::string> kV4Keys{"subsurface_weight", "subsurface_scale", "ior"};
  std::vector<std::string> keys;
  for (const std::string& key : version == 3 ? kV3Keys : kV4Keys)
    if (block.contains(key)) keys.push_back(key);
  const char* method = version == 3 ? "random_walk_fixed_radius" : "random_walk_skin";
  if (block.contains("subsurface_method") && block["subsurface_method"] == method)
    keys.push_back(fmt::format("subsurface_method \"{}\"", method));
  return keys;
}

// Which Principled BSDF a block holds: its "version", else the version whose own keys it has, else 3. Keys of
// both versions, or of the other version than the one given, are refused.
int principled_version(const json& block, const ParamValues& v, const JsonLocation& where) {
  const std::vector<std::string> v3 = version_keys(block, 3);
  const std::vector<std::string> v4 = version_keys(block, 4);
  if (!v3.empty() && !v4.empty())
    fail(where, fmt::format("Blender 3's keys ({}) and Blender 4's keys ({}) in one block; give one version's "
                            "inputs", fmt::join(v3, ", "), fmt::join(v4, ", ")));
  if (!v.has("version")) return v4.empty() ? 3 : 4;
  const int version = v.integer("version");
  const std::vector<std::string>& other = version == 3 ? v4 : v3;
  if (!other.empty())
    fail(where.child("version"), fmt::format("{} (Blender {}'s Principled BSDF) with Blender {}'s keys ({}); give "
                                             "one version's inputs", version, version == 3 ? "3.4" : "4",
                                             version == 3 ? 4 : 3, fmt::join(other, ", ")));
  return version;
}

Material read_principled(const json& block, const JsonLocation& where, double scale_mm) {
  const ParamValues v = read_params(normalized(block, kPrincipledParams), {"principled", kPrincipledParams}, where);
  const int version = principled_version(block, v, where);
  const std::string& method = v.text("subsurface_method");
  if (method == "burley")
    fail(where.child("subsurface_method"), fmt::format("burley: Cycles' Christensen-Burley profile has no medium to "
                                                       "convert; use random_walk or {}",
                                                       version == 3 ? "random_walk_fixed_radius" : "random_walk_skin"));
  if (version == 4) {
    PrincipledV2Subsurface p;
    p.base_color = v.vec3("base_color");
    p.subsurface_weight = static_cast<float>(v.number("subsurface_weight"));
    p.subsurface_radius = v.vec3("subsurface_radius");
    p.subsurface_scale = static_cast<float>(v.number("subsurface_scale"));
    p.ior = static_cast<float>(v.number("ior"));
    p.subsurface_ior = static_cast<float>(v.number("subsurface_ior"));
    p.subsurface_anisotropy = static_cast<float>(v.number("subsurface_anisotropy"));
    p.method = method == "random_walk" ? PrincipledV2Method::RandomWalk : PrincipledV2Method::RandomWalkSkin;
    return principled_v2_subsurface_material(p, scale_mm, where.str()).material;
  }
  PrincipledSubsurface p;
  p.base_color = v.vec3("base_color");
  p.subsurface = static_cast<float>(v.number("subsurface"));
  p.subsurface_radius = v.vec3("subsurface_radius");
  p.subsurface_color = v.vec3("subsurface_color");
  p.subsurface_ior = static_cast<float>(v.number("subsurface_ior"));
  p.subsurface_anisotropy = static_cast<float>(v.number("subsurface_anisotropy"));
  p.method = method == "random_walk" ? PrincipledMethod::RandomWalk : PrincipledMethod::RandomWalkFixedRadius;
  return principled_subsurface_material(p, scale_mm, where.str()).material;
}

Material read_openpbr(const json& block, const JsonLocation& where, double scale_mm, BssrdfModel model) {
  const ParamValues v = read_params(normalized(block, kOpenPbrParams), {"openpbr", kOpenPbrParams}, where);
  OpenPbrSubsurface p;
  p.subsurface_weight = static_cast<float>(v.number("subsurface_weight"));
  p.subsurface_color = v.vec3("subsurface_color");
  p.subsurface_radius = static_cast<float>(v.number("subsurface_radius"));
  p.subsurface_radius_scale = v.vec3("subsurface_radius_scale");
  p.subsurface_scatter_anisotropy = static_cast<float>(v.number("subsurface_scatter_anisotropy"));
  p.specular_ior = static_cast<float>(v.number("specular_ior"));
  const ArtistParameters artist = openpbr_artist_parameters(p, scale_mm, model, where.str());
  return invert_artist_parameters(artist, where.str() + " (subsurface_color as albedo)").material;
}

}  // namespace

const std::span<const ParamDecl> kPrincipledParams{kPrincipled};
const std::span<const ParamDecl> kOpenPbrParams{kOpenPbr};

bool is_shader_material(const json& material) {
  return material.is_object() && (material.contains("principled") || material.contains("openpbr"));
}

Material read_shader_material(const json& material, const JsonLocation& where, double scale_mm) {
  if (material.contains("principled") && material.contains("openpbr"))
    fail(where, "give one of principled and openpbr");
  const char* key = material.contains("principled") ? "principled" : "openpbr";
  const ParamValues outer = read_params(material, {"material", kOuter}, where, {key});
  const BssrdfModel model = *parse_bssrdf_model(outer.text("model"));
  Material m = material.contains("principled") ? read_principled(material.at(key), where.child(key), scale_mm)
                                               : read_openpbr(material.at(key), where.child(key), scale_mm, model);
  m.model = model;
  m.thickness_mm = static_cast<float>(outer.number("thickness_mm"));
  if (!outer.text("name").empty()) m.name = outer.text("name");
  validate_material(m, where.str());
  return m;
}

}  // namespace lucent
