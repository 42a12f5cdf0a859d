// shader_material_json.h: a material given as another renderer's shader parameters, read from JSON (a scene
// file's material object, `lucent materials invert --principled/--openpbr`):
//   {"principled": {<Principled BSDF subsurface inputs: Blender 3.4, or Blender 4 with "version": 4>}}
//                                                       (materials/principled_subsurface.h)
//   {"openpbr": {<OpenPBR Surface subsurface inputs>}, "model": "standard"}  (materials/openpbr_subsurface.h)
// Lengths are in scene units, turned into mm by the scene's scale_mm. Keys and defaults: kPrincipledParams and
// kOpenPbrParams (docs/materials.md).
#pragma once
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "lucent/material.h"
#include "lucent/params.h"
#include "params/param_json.h"

namespace lucent {

extern const std::span<const ParamDecl> kPrincipledParams;
extern const std::span<const ParamDecl> kOpenPbrParams;

// True when `material` is an object with a "principled" or "openpbr" key.
bool is_shader_material(const nlohmann::json& material);

// The material of a {"principled": ...} or {"openpbr": ...} object (which may also hold "model" and "name"
// keys). Throws lucent::Error("<file>: <pointer>: <problem>").
Material read_shader_material(const nlohmann::json& material, const JsonLocation& where, double scale_mm);

}  // namespace lucent
