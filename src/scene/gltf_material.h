// gltf_material.h: glTF 2.0 materials to lucent materials and back (the mapping is docs/materials.md).
//
// Read from the file's JSON (a .gltf, or the JSON chunk of a .glb) with lucent's JSON reader, not through assimp:
// Debian 12's assimp 5.2 does not expose KHR_materials_volume or KHR_materials_diffuse_transmission.
//
//   glTF                                              lucent
//   pbrMetallicRoughness.baseColorFactor (rgb)        surface albedo (the model's flat total reflectance)
//   KHR_materials_volume.attenuationColor c,          sigma_t = -ln(c) / d per band: mean free path
//     attenuationDistance d [m]                         mfp_mm = 1000 d / -ln(c) (c absent: mfp_mm = 1000 d)
//   KHR_materials_volume.thicknessFactor              read, not used: lucent's thickness is the mesh's
//   KHR_materials_ior.ior                             eta (relative to air, n = 1)
//   KHR_materials_diffuse_transmission                marks the material translucent (factor > 0)
//   extras.lucent                                     a scene-file material object: its keys win (g, model,
//                                                     coefficients, a preset, ...)
// A material with none of volume, diffuse transmission or extras.lucent is opaque: the object's albedo is the
// base colour.
#pragma once
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "lucent/material.h"

namespace lucent {

// What the file says, as glTF defines it (defaults filled in).
struct GltfMaterial {
  int index = -1;                              // in the file's "materials"
  std::string name;
  glm::vec3 base_color{1.0f};                  // baseColorFactor rgb (linear), alpha dropped
  bool has_volume = false;                     // KHR_materials_volume
  float thickness_factor = 0.0f;               // [mesh units]
  double attenuation_distance_m = HUGE_VAL;    // [m]
  bool has_attenuation_color = false;
  glm::vec3 attenuation_color{1.0f};
  float ior = 1.5f;                            // KHR_materials_ior (glTF's default 1.5 where absent)
  bool has_diffuse_transmission = false;       // KHR_materials_diffuse_transmission
  float diffuse_transmission_factor = 0.0f;
  glm::vec3 diffuse_transmission_color{1.0f};
  nlohmann::json lucent;                       // extras.lucent, or null
};

// The JSON of a .gltf, or of a .glb's JSON chunk. Throws lucent::Error("<path>: ...") for a missing file, a
// malformed .glb container or malformed JSON.
nlohmann::json read_gltf_json(const std::string& path);

// The one material the file's mesh primitives use, read and range-checked. Throws lucent::Error naming the file
// and the JSON pointer of a bad value, or when the primitives use no material or more than one.
GltfMaterial read_gltf_material(const std::string& path);

// The scene-file material object (the keys scene_loader reads: albedo and mfp_mm, eta, then extras.lucent's keys)
// for a translucent glTF material, or null for an opaque one. Throws lucent::Error("<path>: <pointer>: ...") when a
// translucent material lacks what lucent needs (a base colour in (0, 1), an attenuation distance).
nlohmann::json lucent_material_json(const GltfMaterial& material, const std::string& path);

// A glTF material for a lucent material: base colour = the flat total (the inversion curve's), KHR_materials_volume
// with the largest mean free path as attenuationDistance, KHR_materials_ior, and the exact coefficients in
// extras.lucent. `thickness` [mesh units] becomes thicknessFactor (viewers that approximate volumes use it).
nlohmann::json gltf_material_json(const Material& material, float thickness);
// An opaque object's glTF material: its albedo as the base colour.
nlohmann::json gltf_opaque_material_json(glm::vec3 albedo);

}  // namespace lucent
