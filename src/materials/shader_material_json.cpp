// shader_material_json.cpp: see shader_material_json.h.
#include "materials/shader_material_json.h"

#include <fmt/format.h>

#include "lucent/error.h"
#include "materials/openpbr_subsurface.h"
#include "materials/principled_subsurface.h"

namespace lucent {
namespace {

using nlohmann::json;

// Blender 3.4's Principled BSDF inputs that shape its subsurface, with Blender's defaults.
constexpr ParamDecl kPrincipled[] = {
    {"base_color", ParamType::Vec3, "[0.8, 0.8, 0.8]", "", 0, 1, "", "Base Color (linear RGB), mixed with subsurface_color by subsurface"},
    {"subsurface", ParamType::Float, "1", "", 0, 1, "", "Subsurface: weight; scales the radius and mixes the colours"},
    {"subsurface_radius", ParamType::Vec3, "[1, 0.2, 0.1]", "units", 0, 1e30, "", "Subsurface Radius per band (scene units, times scale_mm)"},
    {"subsurface_color", ParamType::Vec3, "[0.8, 0.8, 0.8]", "", 0, 1, "", "Subsurface Color (linear RGB)"},
    {"subsurface_ior", ParamType::Float, "1.4", "", 1, 3.8, "", "Subsurface IOR: sets the radius (random_walk); the medium is index-matched (eta 1), as in Cycles"},
    {"subsurface_anisotropy", ParamType::Float, "0", "", 0, 1, "", "Subsurface Anisotropy: Henyey-Greenstein g (clamped to 0.9, as Cycles does)"},
    {"subsurface_method", ParamType::Enum, "\"random_walk\"", "", 0, 0, "random_walk|random_walk_fixed_radius|burley",
     "Cycles subsurface method (burley has no medium and is refused)"},
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

Material read_principled(const json& block, const JsonLocation& where, double scale_mm) {
  const ParamValues v = read_params(normalized(block, kPrincipledParams), {"principled", kPrincipledParams}, where);
  if (v.text("subsurface_method") == "burley")
    fail(where.child("subsurface_method"), "burley: Cycles' Christensen-Burley profile has no medium to convert; "
                                           "use random_walk or random_walk_fixed_radius");
  PrincipledSubsurface p;
  p.base_color = v.vec3("base_color");
  p.subsurface = static_cast<float>(v.number("subsurface"));
  p.subsurface_radius = v.vec3("subsurface_radius");
  p.subsurface_color = v.vec3("subsurface_color");
  p.subsurface_ior = static_cast<float>(v.number("subsurface_ior"));
  p.subsurface_anisotropy = static_cast<float>(v.number("subsurface_anisotropy"));
  p.method = v.text("subsurface_method") == "random_walk" ? PrincipledMethod::RandomWalk
                                                          : PrincipledMethod::RandomWalkFixedRadius;
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
