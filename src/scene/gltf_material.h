// gltf_material.h: glTF 2.0 materials to lucent materials and back. The mapping and its reasons are in
// docs/materials.md ("glTF 2.0 materials"); the file is read through tinygltf (scene/gltf_reader.h).
//
// Import, per band, with B = baseColorFactor x baseColorTexture (sRGB decoded), s = transmissionFactor,
// f = diffuseTransmissionFactor, D = diffuseTransmissionColorFactor, KHR_materials_volume's thickness t,
// attenuation distance d [m] and colour c:
//   with KHR_materials_volume_scatter (the medium given whole):
//     sigma_t = -ln(c) / d (1 / d without c), alpha = Kulla-Conty's single-scatter albedo of multiscatterColorFactor,
//     g = scatterAnisotropy: sigma_s = alpha sigma_t, sigma_a = (1 - alpha) sigma_t;
//   otherwise (scattering not given by glTF, absorption by the volume):
//     surface albedo A = (1 - s) ((1 - f) B + f D T) + s B T with T = c^(t / d), the colour glTF's lobes give light
//     that crosses the object's thickness; sigma_a = -ln(c) / d exactly as KHR_materials_volume defines it, and the
//     scattering that makes the model's flat total A: mfp = (1 - alpha(A)) / sigma_a (mfp = d without c).
//   KHR_materials_ior.ior -> eta; extras.lucent: scene-file material keys that win (the exact coefficients).
// A material with none of volume, transmission, diffuse transmission or extras.lucent is opaque.
#pragma once
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "lucent/material.h"
#include "materials/material_maps.h"

namespace lucent {

// The texture coordinates a texture reads: the set (textureInfo.texCoord, or KHR_texture_transform's texCoord, which
// overrides it) and KHR_texture_transform's matrix T(offset) R(rotation) S(scale) applied to glTF's (s, t, 1):
//   s' = cos(r) scale.x s + sin(r) scale.y t + offset.x,   t' = -sin(r) scale.x s + cos(r) scale.y t + offset.y.
// lucent's coordinates are glTF's with t flipped, (u, v) = (s, 1 - t).
struct GltfTextureCoordinates {
  int set = 0;                  // TEXCOORD_<set>
  bool transformed = false;     // the texture has KHR_texture_transform
  glm::dvec2 offset{0.0};
  double rotation = 0.0;        // [radians]
  glm::dvec2 scale{1.0};
  glm::dvec2 gltf(glm::dvec2 st) const;   // glTF's (s, t) -> the transformed (s', t')
  glm::dvec2 lucent(glm::vec2 uv) const;  // lucent's (u, v) -> lucent's coordinates of the transformed ones
};

// What the file says, as glTF defines it (defaults filled in).
struct GltfMaterial {
  std::string path;                            // the glTF file
  int index = -1;                              // in the file's "materials"
  std::string name;
  glm::vec3 base_color{1.0f};                  // baseColorFactor rgb (linear)
  bool has_base_color_factor = false;
  std::optional<MapImage> base_color_texture;  // decoded, linear, rows from v = 0 up
  GltfTextureCoordinates base_color_coordinates;  // the set and transform the texture reads (checked: the set
                                                  // exists on every primitive, the transform's values are finite)
  std::string base_color_texture_at;           // the textureInfo's JSON pointer, for messages
  bool has_transmission = false;               // KHR_materials_transmission
  float transmission_factor = 0.0f;
  bool has_volume = false;                     // KHR_materials_volume
  float thickness_factor = 0.0f;               // [mesh units]
  double mesh_to_world = 1.0;                  // the scale of the first node that instances the mesh (the cube
                                               // root of its world matrix's determinant): thickness in world units
  double attenuation_distance_m = HUGE_VAL;    // [m]
  bool has_attenuation_color = false;
  glm::vec3 attenuation_color{1.0f};
  float ior = 1.5f;                            // KHR_materials_ior (glTF's default 1.5 where absent)
  bool has_diffuse_transmission = false;       // KHR_materials_diffuse_transmission
  float diffuse_transmission_factor = 0.0f;
  glm::vec3 diffuse_transmission_color{1.0f};
  bool has_diffuse_transmission_color = false;
  bool has_volume_scatter = false;             // KHR_materials_volume_scatter (draft)
  bool has_multiscatter_color = false;
  glm::vec3 multiscatter_color{0.0f};          // multiscatterColorFactor (earlier drafts: multiscatterColor)
  float scatter_anisotropy = 0.0f;
  nlohmann::json lucent;                       // extras.lucent, or null
  std::vector<std::string> ignored;            // fields in the file that lucent does not use, for the warning
};

// The one material the file's mesh primitives use, read and range-checked, its base colour texture decoded.
// Throws lucent::Error naming the file and the JSON pointer of a bad value, or when the primitives use no material
// or more than one.
GltfMaterial read_gltf_material(const std::string& path);

// A glTF material as lucent takes it.
struct GltfLucentMaterial {
  nlohmann::json material;                // a scene-file material object, or null for an opaque object
  glm::vec3 opaque_albedo{0.8f};          // the object's albedo when opaque
  std::optional<MapImage> albedo_map;     // the surface albedo A per texel (translucent, textured)
  std::vector<std::string> ignored;       // the material's ignored fields, with the mapping's own
  std::vector<std::string> clamped;       // surface albedos moved into the model's range, for a warning
  // A thin-walled material (KHR_materials_diffuse_transmission without a volume): the sheet's thickness [mm], which
  // the object's surface is thickened to (geometry/sheet_solid.h); 0 for a material with a volume.
  double sheet_thickness_mm = 0.0;
  std::vector<std::string> notes;         // other warnings about the mapping (the sheet's default thickness)
};
// Throws lucent::Error("<path>: <pointer>: ...") at a key of the file when a translucent material lacks what lucent
// needs or a value leaves the ranges lucent's media take.
GltfLucentMaterial lucent_material(const GltfMaterial& material);

// The object's texture coordinates for an albedo map from the base colour texture: `uvs` (lucent's, of set
// base_color_coordinates.set) through the texture's transform (none: unchanged). Throws lucent::Error("<path>: <pointer of the transform>: ...") when a transformed
// coordinate is not a finite float.
void transform_texture_coordinates(const GltfMaterial& material, std::vector<glm::vec2>& uvs);

// "<path>: /materials/<i> ('<name>'): lucent ignores ..." (one line), or "" when nothing is ignored.
std::string ignored_fields_warning(const GltfMaterial& material, const std::vector<std::string>& ignored);

// Kulla and Conty (2017), as KHR_materials_volume_scatter defines it: the single-scatter albedo of a medium whose
// multi-scatter albedo is `multiscatter` (both in [0, 1]), and its inverse (bisection).
double single_scatter_albedo(double multiscatter);
double multiscatter_albedo(double single_scatter);

// The glTF material lucent writes for a lucent material (docs/materials.md, "Export"): base colour = the flat total
// (the inversion curve's), KHR_materials_transmission 1 (lucent's boundary is a smooth dielectric that refracts),
// KHR_materials_volume (attenuation = extinction: colour exp(-sigma_t d) at the largest mean free path d),
// KHR_materials_volume_scatter (multi-scatter albedo of alpha, g's mean), KHR_materials_ior, roughness
// `roughness`, and the exact coefficients in extras.lucent. `thickness` [mesh units] becomes thicknessFactor.
nlohmann::json gltf_material_json(const Material& material, float thickness, float roughness = 0.05f);
// An opaque object's glTF material: its albedo as the base colour.
nlohmann::json gltf_opaque_material_json(glm::vec3 albedo, float roughness = 0.05f);
// The extensions a material object written above uses, for the file's extensionsUsed.
std::vector<std::string> gltf_material_extensions(const nlohmann::json& material);

}  // namespace lucent
