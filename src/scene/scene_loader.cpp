// scene_loader.cpp: JSON scene files -> Scene, validated against the parameter declarations.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <span>

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "denoise/denoise_params.h"
#include "io/file_path_check.h"
#include "lucent/warning.h"
#include "lucent/environment.h"
#include "lucent/error.h"
#include "lucent/output_file.h"
#include "io/input_file.h"
#include "lucent/medium_vdb.h"
#include "lucent/medium_volume.h"
#include "lucent/scene.h"
#include "materials/artist_parameters.h"
#include "materials/material_maps.h"
#include "materials/shader_material_json.h"
#include "scene/gltf_material.h"
#include "scene/gltf_reader.h"
#include "scene/mesh_loader.h"
#include "cache/precompute_cache.h"
#include "geometry/closest_point.h"
#include "geometry/shape_diameter.h"
#include "geometry/sheet_solid.h"
#include "geometry/thickness_grid.h"
#include "scene/mesh_enclosure.h"
#include "methods/method_info.h"
#include "params/param_json.h"

namespace lucent {
namespace {

using nlohmann::json;

constexpr double kPositive = 1e-9;  // lower bound for "strictly positive" ranges

// The largest |x|, |y| or |z| of a vertex in world space [scene units]. The rasterizer and Embree work in float:
// at 1e7 one float step is 1 unit, so geometry further out cannot be placed, shaded or intersected reliably.
constexpr float kMaxWorldCoordinate = 1e7f;

// The smallest sine of the angle between the camera's up and its view direction: below it the camera's roll is
// undefined (the viewer's orbit camera stays 0.01 rad off its poles).
constexpr float kMinUpViewSine = 1e-3f;

constexpr ParamDecl kSceneParams[] = {
    {"scale_mm", ParamType::Float, "1.0", "mm/unit", kPositive, 1e9, "", "millimetres per scene unit"},
    {"comment", ParamType::String, "\"\"", "", 0, 0, "", "free text, ignored"},
};
constexpr ParamDecl kCameraParams[] = {
    {"eye", ParamType::Vec3, "[0, 0, 5]", "units", -1e9, 1e9, "", "camera position"},
    {"target", ParamType::Vec3, "[0, 0, 0]", "units", -1e9, 1e9, "", "point looked at"},
    {"up", ParamType::Vec3, "[0, 1, 0]", "", -1, 1, "", "up direction"},
    {"fov_y_deg", ParamType::Float, "40", "degrees", 1, 179, "", "vertical field of view"},
};
constexpr ParamDecl kLightParams[] = {
    {"type", ParamType::Enum, "\"directional\"", "", 0, 0, "directional|point|spot", "light type"},
    {"direction", ParamType::Vec3, "", "", -1e9, 1e9, "", "directional, spot: direction the light travels (required)"},
    {"radiance", ParamType::Vec3, "", "W/m^2 (RGB)", 0, 1e9, "", "directional: irradiance on a surface facing it (default 1)"},
    {"position", ParamType::Vec3, "", "units", -1e9, 1e9, "", "point, spot: position (required)"},
    {"intensity", ParamType::Vec3, "", "W/sr (RGB)", 0, 1e9, "", "point, spot: radiant intensity (default 1e-3); irradiance I/d^2, d in m"},
    {"inner_deg", ParamType::Float, "", "degrees", 0, 90, "", "spot: full intensity within this half-angle (default 30)"},
    {"outer_deg", ParamType::Float, "", "degrees", 0, 90, "", "spot: no light beyond this half-angle (default 45)"},
};
constexpr ParamDecl kEnvironmentParams[] = {
    {"file", ParamType::String, "", "", 0, 0, "", "equirectangular .hdr or .exr map, relative to the scene (required)"},
    {"lights", ParamType::Int, "8", "lights", 1, 16, "", "M directional lights the map is sampled into"},
    {"intensity", ParamType::Float, "1", "", 0, 1e9, "", "scale on the map's radiance"},
    {"background", ParamType::Bool, "true", "", 0, 1, "", "camera rays that miss the scene see the map"},
};
constexpr ParamDecl kDeformParams[] = {
    {"type", ParamType::Enum, "\"bend\"", "", 0, 0, "bend|melt|wave", "per-frame vertex deformation"},
    {"amplitude", ParamType::Float, "0.3", "units", 0, 1e9, "", "bend, wave: sideways sway at the top; melt: fraction of height lost (< 1)"},
    {"period_s", ParamType::Float, "4", "s", 1e-3, 1e6, "", "one cycle"},
    {"start_s", ParamType::Float, "0", "s", -1e6, 1e6, "",
     "time in the cycle at render time 0 (a still image of a bent pose: a quarter period)"},
};
constexpr ParamDecl kObjectParams[] = {
    {"name", ParamType::String, "\"\"", "", 0, 0, "", "name used in messages"},
    {"shape", ParamType::Enum, "\"\"", "", 0, 0, "|sphere|shell|torus|box|plane|lathe|blobs",
     "procedural shape (or give mesh); lathe revolves \"profile\": [[r, y], ...] (units, r >= 0) about y"},
    {"mesh", ParamType::String, "\"\"", "", 0, 0, "", "mesh file (OBJ, PLY, glTF, STL, 3DS, ...), relative to the scene"},
    {"radius", ParamType::Float, "1", "units", kPositive, 1e9, "", "sphere and shell radius"},
    {"inner_radius", ParamType::Float, "0.8", "units", kPositive, 1e9, "", "shell: radius of the hollow inside"},
    {"major_radius", ParamType::Float, "1", "units", kPositive, 1e9, "", "torus: ring radius"},
    {"minor_radius", ParamType::Float, "0.4", "units", kPositive, 1e9, "", "torus: tube radius"},
    {"size", ParamType::Vec3, "[1, 1, 1]", "units", kPositive, 1e9, "", "box edge lengths"},
    {"extent", ParamType::Vec2, "[10, 10]", "units", kPositive, 1e9, "", "plane size along x and z"},
    {"segments", ParamType::Int, "64", "", 3, 4096, "", "tessellation of spheres, tori and lathes; blobs: grid cells along the long axis"},
    {"translate", ParamType::Vec3, "[0, 0, 0]", "units", -1e9, 1e9, "", "translation"},
    {"rotate_deg", ParamType::Vec3, "[0, 0, 0]", "degrees", -1e4, 1e4, "", "rotation about x, then y, then z"},
    {"scale", ParamType::Float, "1", "", kPositive, 1e9, "", "uniform scale"},
    {"up_axis", ParamType::Enum, "\"y\"", "", 0, 0, "y|z|-z|x|-x|-y",
     "the object's up axis, turned to +y before its own transform (z: Blender, 3ds Max exports)"},
    {"albedo", ParamType::Vec3, "[0.8, 0.8, 0.8]", "", 0, 1, "", "diffuse albedo of an opaque object"},
};
constexpr ParamDecl kMaterialParams[] = {
    {"preset", ParamType::String, "\"\"", "", 0, 0, "", "measured material name (lucent materials)"},
    {"sigma_a", ParamType::Vec3, "", "mm^-1", -1e30, 1e30, "", "absorption coefficient"},
    {"sigma_s", ParamType::Vec3, "", "mm^-1", -1e30, 1e30, "", "scattering coefficient (unreduced, with g)"},
    {"sigma_s_prime", ParamType::Vec3, "", "mm^-1", -1e30, 1e30, "", "reduced scattering (instead of sigma_s, g)"},
    {"g", ParamType::Vec3, "", "", -1e30, 1e30, "", "Henyey-Greenstein g per band (a number sets all three)"},
    {"eta", ParamType::Float, "", "", 1, 3, "", "relative refractive index n_material / n_outside (default: preset, or 1.3)"},
    {"model", ParamType::Enum, "\"standard\"", "", 0, 0, "standard|directional|photon-beam|better-dipole|tabulated|multipole", "diffusion model S_d (default: kDefaultBssrdfModel, the closest to volpath measured)"},
    {"thickness_mm", ParamType::Float, "0", "mm", 0, 1e30, "", "the thickness of the part, for the multipole model's reflectance (its transmittance takes the distance between the faces a light path joins); 0: reflect as a half-space"},
    {"thickness_from_mesh", ParamType::Bool, "false", "", 0, 1, "", "the multipole model's thickness measured on the object's mesh per surface point (its shape diameter, read as a slab's thickness); thickness_mm becomes its median"},
    {"albedo", ParamType::Vec3, "", "", -1e30, 1e30, "", "surface albedo: the thick-slab total diffuse reflectance (with mfp_mm, instead of coefficients); a thinner object than the diffusion length shows less of it"},
    {"mfp_mm", ParamType::Vec3, "", "mm", -1e30, 1e30, "", "mean free path 1 / sigma_t, unreduced (with albedo, instead of coefficients)"},
    {"albedo_map", ParamType::String, "\"\"", "", 0, 0, "",
     "surface albedo per texel through the mesh's texture coordinates (.png sRGB, .exr, .hdr; with mfp_mm, instead of albedo)"},
    {"mfp_map", ParamType::String, "\"\"", "", 0, 0, "",
     "factor on the mean free path per texel (.png linear, .exr, .hdr)"},
};
constexpr ParamDecl kFieldParams[] = {
    {"type", ParamType::Enum, "\"none\"", "", 0, 0, "none|marble|layered|volume|vdb",
     "heterogeneous medium: density multiplier m(x); sigma_t m, sigma_s min(m, 1) (voxel-paths and volpath)"},
    {"scale_mm", ParamType::Float, "10", "mm", 1e-3, 1e6, "", "marble: vein period; layered: outer-layer thickness"},
    {"contrast", ParamType::Float, "4", "", 0, 1000, "", "marble, layered: m ranges over [1, 1 + contrast]"},
    {"file", ParamType::String, "\"\"", "", 0, 0, "", "volume: JSON header of a raw grid of m (lucent/medium_volume.h); vdb: an OpenVDB file (lucent/medium_vdb.h)"},
    {"grid", ParamType::String, "\"density\"", "", 0, 0, "", "vdb: name of the float grid"},
    {"density_scale", ParamType::Float, "1", "", 0, 1e6, "", "vdb: m = density_scale * grid value"},
    {"transform", ParamType::Enum, "\"object-bounds\"", "", 0, 0, "object-bounds|vdb-world",
     "vdb: the active voxels span the object's bounds, or the VDB's world coordinates are scene units"},
};
constexpr ParamDecl kRenderParams[] = {
    {"width", ParamType::Int, "640", "pixels", 1, 16384, "", "image width"},
    {"height", ParamType::Int, "480", "pixels", 1, 16384, "", "image height"},
    {"frames", ParamType::Int, "1", "frames", 1, 1000000, "", "frames accumulated by lucent render"},
    {"seed", ParamType::Int, "1", "", 0, 4294967295.0, "", "random seed"},
    {"exposure", ParamType::Float, "0", "stops", -30, 30, "", "exposure before tone mapping"},
    {"tonemap", ParamType::Enum, "\"aces\"", "", 0, 0, "aces|reinhard|linear", "tone-mapping operator"},
    {"background", ParamType::Vec3, "[0, 0, 0]", "radiance", 0, 1e9, "", "radiance behind the scene"},
    {"fps", ParamType::Float, "30", "frames/s", 1e-3, 1e4, "", "animation frame rate (lucent render --animate)"},
};

// The file the scene names in `key`, refused when it cannot name a file (a NUL byte would cut it).
const std::string& file_param(const ParamValues& v, const char* key, const JsonLocation& where) {
  const std::string& file = v.text(key);
  if (const std::string problem = file_path_problem(file); !problem.empty()) fail(where.child(key), problem);
  return file;
}

// A path as the scene file gives it, relative to the scene's folder.
std::string resolve_path(const std::string& file, const std::string& base_dir) {
  std::filesystem::path path = file;
  if (path.is_relative()) path = std::filesystem::path(base_dir) / path;
  return path.lexically_normal().string();
}

glm::vec3 unit(glm::vec3 v, const JsonLocation& where) {
  float len = glm::length(v);
  if (!(len > 1e-12f)) fail(where, "must be a non-zero vector");
  return v / len;
}

Camera read_camera(const json& j, const JsonLocation& where) {
  ParamValues v = read_params(j, {"camera", kCameraParams}, where);
  Camera camera;
  camera.eye = v.vec3("eye");
  camera.target = v.vec3("target");
  camera.up = unit(v.vec3("up"), where.child("up"));
  camera.fov_y_deg = static_cast<float>(v.number("fov_y_deg"));
  if (glm::length(camera.eye - camera.target) < 1e-9f) fail(where.child("target"), "equals eye");
  if (glm::length(glm::cross(glm::normalize(camera.target - camera.eye), camera.up)) < kMinUpViewSine)
    fail(where.child("up"), "parallel to the view direction from eye to target");
  return camera;
}

// Reads one light into the scene's directional or point lights. Keys that the light's type does not use are
// errors, so that a misspelt type cannot silently drop a position or a direction.
void read_light(const json& j, const JsonLocation& where, Scene& scene) {
  ParamValues v = read_params(j, {"light", kLightParams}, where);
  const std::string& type = v.text("type");
  auto forbid = [&](std::initializer_list<const char*> keys) {
    for (const char* key : keys)
      if (v.has(key)) fail(where.child(key), fmt::format("not used by a {} light", type));
  };
  auto require = [&](const char* key, const char* example) {
    if (!v.has(key)) fail(where.child(key), fmt::format("missing; a {} light needs it, e.g. {}", type, example));
  };
  if (type == "directional") {
    forbid({"position", "intensity", "inner_deg", "outer_deg"});
    require("direction", "[0, -1, 0] (the direction the light travels)");
    scene.lights.push_back({unit(v.vec3("direction"), where.child("direction")),
                            v.has("radiance") ? v.vec3("radiance") : glm::vec3(1.0f)});
    return;
  }
  forbid({"radiance"});
  require("position", "[0, 1, 0]");
  PointLight light;
  light.position = v.vec3("position");
  light.intensity = v.has("intensity") ? v.vec3("intensity") : glm::vec3(1e-3f);
  if (type == "point") {
    forbid({"direction", "inner_deg", "outer_deg"});
  } else {
    require("direction", "[0, -1, 0] (the spot's axis, the direction the light travels)");
    light.spot = true;
    light.direction = unit(v.vec3("direction"), where.child("direction"));
    if (v.has("inner_deg")) light.inner_deg = static_cast<float>(v.number("inner_deg"));
    if (v.has("outer_deg")) light.outer_deg = static_cast<float>(v.number("outer_deg"));
    if (light.inner_deg > light.outer_deg)
      fail(where.child("inner_deg"), fmt::format("{} exceeds outer_deg {}", light.inner_deg, light.outer_deg));
  }
  scene.point_lights.push_back(light);
}

// Loads the map, scales it and appends its M directional lights to the scene.
void read_environment(const json& j, const JsonLocation& where, const std::string& base_dir, Scene& scene) {
  ParamValues v = read_params(j, {"environment", kEnvironmentParams}, where);
  if (!v.has("file") || v.text("file").empty()) fail(where.child("file"), "missing; an .hdr or .exr map");
  EnvironmentLight env;
  std::filesystem::path path = file_param(v, "file", where);
  if (path.is_relative()) path = std::filesystem::path(base_dir) / path;
  env.file = path.lexically_normal().string();
  env.light_count = v.integer("lights");
  env.intensity = static_cast<float>(v.number("intensity"));
  env.background = v.boolean("background");
  auto map = std::make_shared<EnvironmentMap>();
  try {
    *map = load_environment_map(env.file);
  } catch (const Error& e) {
    fail(where.child("file"), e.what());
  }
  for (glm::vec3& L : map->radiance) L *= env.intensity;
  for (DirectionalLight light : environment_to_directional_lights(*map, env.light_count)) {
    light.specular = false;
    scene.lights.push_back(light);
  }
  env.map = std::move(map);
  scene.environment = std::move(env);
}

// What the loader and check_material_maps refuse about a textured material, worded once: the map key it names and
// the problem ("" for none).
const char* map_key(const MaterialMaps& maps) { return maps.albedo_file.empty() ? "mfp_map" : "albedo_map"; }
// Why a model read from tables cannot take a texture ("" for the others).
std::string table_model_maps_problem(BssrdfModel model, const char* key) {
  if (model != BssrdfModel::Tabulated && model != BssrdfModel::Multipole) return "";
  return fmt::format("{} takes no {}: its tables hold one medium each, a texture has a medium per texel",
                     to_string(model), key);
}
std::string texture_coordinates_problem(const SceneObject& object) {
  if (object.blob_resolution == 0 && !object.mesh.uvs.empty()) return "";
  return fmt::format("a texture needs the mesh's texture coordinates; {} has none",
                     object.blob_resolution > 0 ? "a blob surface"
                     : object.mesh_file.empty() ? "the shape" : object.mesh_file);
}

json normalized_material(const json& j) {
  json copy = j;
  for (const char* key : {"g", "albedo", "mfp_mm"})
    if (copy.contains(key) && copy[key].is_number()) copy[key] = json::array({copy[key], copy[key], copy[key]});
  return copy;
}

MediumField read_field(const json& j, const JsonLocation& where, const std::string& base_dir) {
  ParamValues v = read_params(j, {"field", kFieldParams}, where);
  MediumField field;
  const std::string& type = v.text("type");
  field.type = type == "marble"    ? MediumFieldType::Marble
               : type == "layered" ? MediumFieldType::Layered
               : type == "volume"  ? MediumFieldType::Volume
                                   : MediumFieldType::None;
  field.scale_mm = static_cast<float>(v.number("scale_mm"));
  field.contrast = static_cast<float>(v.number("contrast"));
  field.file = file_param(v, "file", where);
  for (const char* key : {"grid", "density_scale", "transform"})
    if (j.contains(key) && type != "vdb") fail(where.child(key), fmt::format("only for type vdb (type is {})", type));
  if (type == "vdb") {
    if (field.file.empty()) fail(where.child("file"), "a vdb field needs the file of its OpenVDB grid");
    VdbField vdb;
    std::filesystem::path path = field.file;
    if (path.is_relative()) path = std::filesystem::path(base_dir) / path;
    vdb.file = path.string();
    vdb.grid = v.text("grid");
    vdb.density_scale = static_cast<float>(v.number("density_scale"));
    vdb.transform = v.text("transform") == "vdb-world" ? VdbTransform::VdbWorld : VdbTransform::ObjectBounds;
    require_regular_file(vdb.file);
    VdbVolume loaded = load_medium_vdb(vdb);
    field.type = MediumFieldType::Volume;  // resampled into a dense volume: voxel-paths and volpath read it as one
    field.volume = std::move(loaded.volume);
    if (loaded.world) field.has_bounds = true, field.bounds_lower = loaded.lower, field.bounds_upper = loaded.upper;
  } else if (field.type == MediumFieldType::Volume) {
    if (field.file.empty()) fail(where.child("file"), "a volume field needs the file of its JSON header");
    std::filesystem::path path = field.file;
    if (path.is_relative()) path = std::filesystem::path(base_dir) / path;
    field.volume = load_medium_volume(path.string());
  } else if (!field.file.empty()) {
    fail(where.child("file"), fmt::format("only for types volume and vdb (type is {})", type));
  }
  return field;
}

// Coefficients from a preset or given directly.
Material material_from_coefficients(const ParamValues& v, const JsonLocation& where) {
  const std::string& preset_name = v.text("preset");
  bool explicit_coefficients = v.has("sigma_a") || v.has("sigma_s") || v.has("sigma_s_prime") || v.has("g");
  if (!preset_name.empty()) {
    if (explicit_coefficients) fail(where, "give either preset or coefficients, not both");
    const MaterialPreset* preset = find_material_preset(preset_name);
    if (!preset)
      fail(where.child("preset"),
           fmt::format("unknown material '{}' (see: lucent materials)", text_excerpt(preset_name)));
    return material_from_preset(*preset);
  }
  if (!v.has("sigma_a"))
    fail(where, "needs preset, or sigma_a with sigma_s (and g) or sigma_s_prime, or albedo with mfp_mm");
  if (v.has("sigma_s") == v.has("sigma_s_prime")) fail(where, "give exactly one of sigma_s and sigma_s_prime");
  if (v.has("sigma_s_prime") && v.has("g")) fail(where.child("g"), "not allowed with sigma_s_prime (reduced, g = 0)");
  Material m;
  m.sigma_a = v.vec3("sigma_a");
  m.sigma_s = v.has("sigma_s") ? v.vec3("sigma_s") : v.vec3("sigma_s_prime");
  m.g = v.has("g") ? v.vec3("g") : glm::vec3(0.0f);
  return m;
}

// Coefficients inverted from the surface albedo and the mean free path (materials/artist_parameters.h). With an
// albedo map, `map_albedo` (its mean) stands in for the albedo.
Material material_from_artist(const ParamValues& v, const JsonLocation& where, const glm::vec3* map_albedo) {
  for (const char* key : {"preset", "sigma_a", "sigma_s", "sigma_s_prime"})
    if (v.has(key) && !(key == std::string_view("preset") && v.text("preset").empty()))
      fail(where.child(key), "not allowed with albedo and mfp_mm (give either albedo and mfp_mm or coefficients)");
  if (map_albedo && v.has("albedo"))
    fail(where.child("albedo"), "not allowed with albedo_map (the map is the surface albedo)");
  if (!map_albedo && !v.has("albedo"))
    fail(where.child("albedo"), "missing; mfp_mm needs the surface albedo too, e.g. [0.8, 0.6, 0.5]");
  if (!v.has("mfp_mm"))
    fail(where.child("mfp_mm"), map_albedo ? "missing; albedo_map needs the mean free path too, e.g. [1, 0.5, 0.25]"
                                           : "missing; albedo needs the mean free path too, e.g. [1, 0.5, 0.25]");
  ArtistParameters artist;
  artist.albedo = map_albedo ? *map_albedo : v.vec3("albedo");
  artist.mfp_mm = v.vec3("mfp_mm");
  if (v.has("g")) artist.g = v.vec3("g");
  if (v.has("eta")) artist.eta = static_cast<float>(v.number("eta"));
  artist.model = *parse_bssrdf_model(v.text("model"));
  return invert_artist_parameters(artist, where.str()).material;
}

// A map's file from the material's key ("" when absent or empty).
std::optional<MapImage> read_map_key(const ParamValues& v, const char* key, bool colour, const JsonLocation& where,
                                     const std::string& base_dir) {
  if (!v.has(key) || v.text(key).empty()) return std::nullopt;
  return read_material_map(resolve_path(file_param(v, key, where), base_dir), colour, where.child(key).str());
}

// The middle of the albedos the material's model reaches, for an albedo map's mean outside them (the texels are
// clamped and counted in make_material_maps; the mean only sets the base coefficients).
glm::vec3 reachable_mean_albedo(glm::vec3 mean, const ParamValues& v) {
  const BssrdfModel curve = inversion_curve_model(*parse_bssrdf_model(v.text("model")));
  const float eta = v.has("eta") ? static_cast<float>(v.number("eta")) : ArtistParameters{}.eta;
  const glm::vec3 g = v.has("g") ? v.vec3("g") : glm::vec3(0.0f);
  for (int c = 0; c < 3; ++c) {
    if (!(std::abs(g[c]) < 1.0f) || !(eta >= 1.0f && eta <= 3.0f)) continue;  // reported by the inversion
    const double lo = flat_total_of_albedo(curve, kArtistAlphaMin, g[c], eta);
    const double hi = std::min(1.0, flat_total_of_albedo(curve, kArtistAlphaMax, g[c], eta));
    mean[c] = static_cast<float>(std::clamp<double>(mean[c], lo + 1e-3 * (hi - lo), hi - 1e-3 * (hi - lo)));
  }
  return mean;
}

// `scale_mm` turns the lengths of a principled or openpbr block (scene units) into mm.
Material read_material(const json& raw, const JsonLocation& where, const std::string& base_dir,
                       double scale_mm = 1.0) {
  if (is_shader_material(raw)) return read_shader_material(raw, where, scale_mm);
  json j = raw.is_string() ? json{{"preset", raw}} : normalized_material(raw);
  ParamValues v = read_params(j, {"material", kMaterialParams}, where, {"field"});
  const std::optional<MapImage> albedo_map = read_map_key(v, "albedo_map", true, where, base_dir);
  const std::optional<MapImage> mfp_map = read_map_key(v, "mfp_map", false, where, base_dir);
  const bool artist = v.has("albedo") || v.has("mfp_mm") || albedo_map;
  std::optional<glm::vec3> map_albedo;
  if (albedo_map) map_albedo = reachable_mean_albedo(map_mean(*albedo_map), v);
  Material m = artist ? material_from_artist(v, where, map_albedo ? &*map_albedo : nullptr)
                      : material_from_coefficients(v, where);
  if (v.has("eta")) m.eta = static_cast<float>(v.number("eta"));
  m.model = *parse_bssrdf_model(v.text("model"));
  m.thickness_mm = static_cast<float>(v.number("thickness_mm"));
  if (j.contains("field")) m.field = read_field(j.at("field"), where.child("field"), base_dir);
  if (albedo_map || mfp_map) {
    const char* key = albedo_map ? "albedo_map" : "mfp_map";
    if (m.field.heterogeneous())
      fail(where.child("field"), fmt::format("not with {}: a material is textured or has a 3D field, not both", key));
    if (const std::string problem = table_model_maps_problem(m.model, key); !problem.empty())
      fail(where.child("model"), problem);
    validate_material(m, where.str());
    std::shared_ptr<MaterialMaps> maps =
        make_material_maps(m, albedo_map ? &*albedo_map : nullptr, mfp_map ? &*mfp_map : nullptr, where.str());
    if (mfp_map) {  // the material's own coefficients: those at the map's mean factor
      const glm::vec3 scale = map_mean(*mfp_map);
      for (int c = 0; c < 3; ++c)
        if (scale[c] > 0.0f) m.sigma_a[c] /= scale[c], m.sigma_s[c] /= scale[c];
    }
    maps->made_with_sigma_a = m.sigma_a, maps->made_with_sigma_s = m.sigma_s;
    m.maps = std::move(maps);
  }
  validate_medium(m, where.str());  // what the diffusion models need besides: once the method is known
  return m;
}

// A lathe profile: an array of [r, y] pairs with r >= 0, finite.
std::vector<glm::vec2> read_profile(const json& object, const JsonLocation& where) {
  std::vector<glm::vec2> profile;
  if (!object.contains("profile")) return profile;
  const json& p = object["profile"];
  JsonLocation at = where.child("profile");
  if (!p.is_array()) fail(at, "expected an array of [r, y] points");
  for (std::size_t i = 0; i < p.size(); ++i) {
    const json& q = p[i];
    if (!q.is_array() || q.size() != 2 || !q[0].is_number() || !q[1].is_number())
      fail(at.child(i), "expected [r, y] (two numbers)");
    const double r = q[0].get<double>(), y = q[1].get<double>();
    auto fits_float = [](double x) { return std::abs(x) <= std::numeric_limits<float>::max(); };  // false for NaN
    if (!fits_float(r) || !fits_float(y) || r < 0.0)
      fail(at.child(i), fmt::format("[{}, {}]: r must be >= 0 and both finite", excerpt(q[0]), excerpt(q[1])));
    profile.emplace_back(static_cast<float>(r), static_cast<float>(y));
  }
  return profile;
}

TriangleMesh read_geometry(const ParamValues& v, const std::vector<glm::vec2>& profile, const JsonLocation& where,
                           const std::string& base_dir) {
  const std::string& shape = v.text("shape");
  const std::string& mesh = file_param(v, "mesh", where);
  if (shape.empty() == mesh.empty()) fail(where, "give exactly one of shape and mesh");
  int segments = v.integer("segments");
  if (shape == "blobs") return {};  // extracted every frame (SceneObject::blob_resolution)
  if (!profile.empty() && shape != "lathe") fail(where.child("profile"), "only used by shape lathe");
  if (shape == "sphere") return make_sphere(static_cast<float>(v.number("radius")), segments / 2, segments);
  if (shape == "torus")
    return make_torus(static_cast<float>(v.number("major_radius")), static_cast<float>(v.number("minor_radius")),
                      segments, segments / 2);
  if (shape == "shell") {
    if (v.number("inner_radius") >= v.number("radius"))
      fail(where.child("inner_radius"), fmt::format("{} must be smaller than radius {}", v.number("inner_radius"), v.number("radius")));
    return make_shell(static_cast<float>(v.number("radius")), static_cast<float>(v.number("inner_radius")), segments);
  }
  if (shape == "lathe") {
    if (profile.size() < 3) fail(where.child("profile"), "lathe needs a profile of at least 3 [r, y] points");
    return make_lathe(profile, segments);
  }
  if (shape == "box") return make_box(v.vec3("size"));
  if (shape == "plane") return make_plane(glm::vec2(v.vec3("extent")));
  try {
    return load_mesh(resolve_path(mesh, base_dir));
  } catch (const Error& e) {
    fail(where.child("mesh"), e.what());
  }
}

// Normals that point into a closed object would render it black: flip them and say so.
void orient_normals_outward(TriangleMesh& mesh, const std::string& what) {
  glm::vec3 centroid(0.0f);
  for (const glm::vec3& p : mesh.positions) centroid += p;
  centroid /= static_cast<float>(mesh.positions.size());
  double outwardness = 0.0;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    outwardness += glm::dot(mesh.normals[i], mesh.positions[i] - centroid);
  if (outwardness >= 0.0) return;
  for (glm::vec3& n : mesh.normals) n = -n;
  warn(what + ": normals point inward; flipped");
}

// Every vertex in world space within kMaxWorldCoordinate (which also excludes inf and NaN).
void check_world_extent(const TriangleMesh& mesh, const glm::mat4& world_from_object, const JsonLocation& where) {
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    glm::vec3 p = glm::vec3(world_from_object * glm::vec4(mesh.positions[i], 1.0f));
    bool inside = std::abs(p.x) <= kMaxWorldCoordinate && std::abs(p.y) <= kMaxWorldCoordinate &&
                  std::abs(p.z) <= kMaxWorldCoordinate;
    if (!inside)
      fail(where, fmt::format("vertex {} is at ({:g}, {:g}, {:g}) in world space, beyond {:g} scene units "
                              "(float precision)", i, p.x, p.y, p.z, kMaxWorldCoordinate));
  }
}

// The rotation that takes the object's up axis to +y: z maps (x, y, z) to (x, z, -y), as Blender's Y-up exporters
// do; x turns about z, -y about x by 180 degrees.
glm::mat4 up_axis_rotation(const std::string& up) {
  const float quarter = glm::half_pi<float>();
  if (up == "z") return glm::rotate(glm::mat4(1.0f), -quarter, glm::vec3(1, 0, 0));
  if (up == "-z") return glm::rotate(glm::mat4(1.0f), quarter, glm::vec3(1, 0, 0));
  if (up == "x") return glm::rotate(glm::mat4(1.0f), quarter, glm::vec3(0, 0, 1));
  if (up == "-x") return glm::rotate(glm::mat4(1.0f), -quarter, glm::vec3(0, 0, 1));
  if (up == "-y") return glm::rotate(glm::mat4(1.0f), 2.0f * quarter, glm::vec3(1, 0, 0));
  return glm::mat4(1.0f);
}

glm::mat4 read_transform(const ParamValues& v) {
  glm::vec3 r = glm::radians(v.vec3("rotate_deg"));
  glm::mat4 m = glm::translate(glm::mat4(1.0f), v.vec3("translate"));
  m = glm::rotate(m, r.z, glm::vec3(0, 0, 1));
  m = glm::rotate(m, r.y, glm::vec3(0, 1, 0));
  m = glm::rotate(m, r.x, glm::vec3(1, 0, 0));
  m = glm::scale(m, glm::vec3(static_cast<float>(v.number("scale"))));
  return m * up_axis_rotation(v.text("up_axis"));
}

// A glTF base colour texture as the material's albedo map (the surface albedo per texel, docs/materials.md), as
// read_material makes an albedo_map's: the material's coefficients are those of the texels' mean.
void attach_albedo_map(Material& m, const MapImage& albedo, const JsonLocation& where) {
  if (m.field.heterogeneous())
    fail(where.child("field"), "not with a base colour texture: a material is textured or has a 3D field, not both");
  if (const std::string problem = table_model_maps_problem(m.model, "albedo_map"); !problem.empty())
    fail(where.child("model"), problem);
  std::shared_ptr<MaterialMaps> maps = make_material_maps(m, &albedo, nullptr, where.str());
  maps->made_with_sigma_a = m.sigma_a, maps->made_with_sigma_s = m.sigma_s;
  m.maps = std::move(maps);
}

// "material": "from_mesh": the material of the object's glTF mesh (scene/gltf_material.h); an opaque glTF material
// makes the object opaque with its base colour. One warning line names the fields lucent does not use.
constexpr const char* kFromMesh = "from_mesh";
void read_mesh_material(SceneObject& object, const JsonLocation& where, double scale_mm) {
  const std::filesystem::path mesh = object.mesh_file;
  std::string extension = mesh.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension != ".gltf" && extension != ".glb")
    fail(where.child("material"), "\"from_mesh\" needs a glTF mesh (.gltf or .glb)");
  GltfLucentMaterial mapped;
  try {
    const GltfMaterial gltf = read_gltf_material(object.mesh_file);
    mapped = lucent_material(gltf);
    if (const std::string fields = ignored_fields_warning(gltf, mapped.ignored); !fields.empty()) warn(fields);
    for (const std::string& clamped : mapped.clamped)
      warn(fmt::format("{}: /materials/{}: {}", object.mesh_file, gltf.index, clamped));
    for (const std::string& note : mapped.notes) warn(fmt::format("{}: /materials/{}: {}", object.mesh_file, gltf.index, note));
    if (mapped.material.is_null()) {
      object.albedo = mapped.opaque_albedo;
      return;
    }
    const JsonLocation at{object.mesh_file, fmt::format("/materials/{}", gltf.index)};
    object.material = read_material(mapped.material, at, mesh.parent_path().string());
    if (!gltf.name.empty() && !mapped.material.contains("preset")) object.material->name = gltf.name;
    if (mapped.sheet_thickness_mm > 0.0) {  // thin-walled: the surface thickened into a sheet (or a hollow shell)
      const double object_scale = std::cbrt(std::abs(glm::determinant(glm::mat3(object.world_from_object))));
      object.mesh = sheet_solid(object.mesh, static_cast<float>(mapped.sheet_thickness_mm / scale_mm / object_scale));
    }
    if (mapped.albedo_map) {  // the texture's coordinates: its set (the mesh was read with set 0) and transform
      if (const int set = gltf.base_color_coordinates.set; set != 0) {
        TriangleMesh with_set = load_mesh_with_uv_set(object.mesh_file, static_cast<unsigned>(set));
        if (with_set.positions.size() != object.mesh.positions.size() || with_set.uvs.size() != with_set.positions.size())
          throw Error(fmt::format("{}: TEXCOORD_{}: the mesh read with this set differs from the mesh", object.mesh_file, set));
        object.mesh.uvs = std::move(with_set.uvs);
      }
      transform_texture_coordinates(gltf, object.mesh.uvs);
    }
  } catch (const Error& e) {
    fail(where.child("material"), e.what());
  }
  if (mapped.albedo_map) attach_albedo_map(*object.material, *mapped.albedo_map, where.child("material"));
}

// The largest of the mean free paths [mm] of objects that took their glTF material, against the object's smallest
// world extent [mm]: at a quarter of it or more, light crosses the object in a few steps and the diffusion models'
// semi-infinite medium is a poor stand-in (the image shows the light that leaves the far side missing).
constexpr float kComparableMeanFreePath = 0.25f;  // mfp / smallest extent
void warn_about_gltf_mean_free_paths(const json& objects, const Scene& scene) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    if (!objects[i].is_object() || objects[i].value("material", json()) != kFromMesh || !object.material) continue;
    glm::vec3 lo(HUGE_VALF), hi(-HUGE_VALF);
    for (const glm::vec3& p : transformed(object.mesh, object.world_from_object).positions)
      lo = glm::min(lo, p), hi = glm::max(hi, p);
    const glm::vec3 size = hi - lo;
    const float extent_mm = std::min({size.x, size.y, size.z}) * scene.scale_mm;
    const glm::vec3 mfp = 1.0f / object.material->sigma_t();
    if (std::max({mfp.x, mfp.y, mfp.z}) < kComparableMeanFreePath * extent_mm) continue;
    if (object.material->model == BssrdfModel::Multipole) continue;  // its slab has the part's thickness
    warn(fmt::format("{}: /objects/{}: the mean free path ({:.3g}, {:.3g}, {:.3g}) mm of {}'s material is comparable to "
                     "or larger than the object, {:.3g} mm across at its thinnest (scale_mm {:g}): light crosses it in "
                     "a few scattering steps, which the diffusion models do not see (volpath does)",
                     scene.source, i, mfp.x, mfp.y, mfp.z, object.mesh_file, extent_mm, scene.scale_mm));
  }
}

bool thickness_from_mesh(const json& material) {
  return material.is_object() && material.value("thickness_from_mesh", false);
}

// `"thickness_from_mesh": true`: the part's thickness from its mesh (after its transform), the shape diameter of
// each triangle read as a slab's thickness (geometry/shape_diameter.h): per surface point through the object's
// thickness grid (geometry/thickness_field.h), and its area-weighted median as the material's thickness_mm [mm].
void measure_thickness(SceneObject& object, const JsonLocation& where, double scale_mm) {
  if (object.material->thickness_mm > 0.0f)
    fail(where.child("thickness_from_mesh"), "not with thickness_mm: the thickness is given or measured, not both");
  if (object.blob_resolution > 0) fail(where.child("thickness_from_mesh"), "not for blobs (their surface is extracted per frame)");
  // Cached with the precomputations (13 s for the 69k-triangle bunny on two cores): the median, the area share and
  // the value of every triangle.
  cache::Key key("shape-diameter", 2);
  key.mesh(object.mesh);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) key.number(object.world_from_object[c][r]);
  ShapeDiameter diameter;
  const std::size_t triangles = object.mesh.indices.size() / 3;
  if (std::optional<std::vector<std::byte>> bytes = cache::load(key);
      bytes && bytes->size() == (2 + triangles) * sizeof(double)) {
    std::vector<double> cached(2 + triangles);
    std::memcpy(cached.data(), bytes->data(), bytes->size());
    diameter.median = cached[0], diameter.measured_area_fraction = cached[1];
    diameter.per_triangle.assign(cached.begin() + 2, cached.end());
  } else {
    try {
      diameter = shape_diameter(object.mesh, object.world_from_object);
    } catch (const Error& e) {
      fail(where.child("thickness_from_mesh"), e.what());
    }
    std::vector<double> cached{diameter.median, diameter.measured_area_fraction};
    cached.insert(cached.end(), diameter.per_triangle.begin(), diameter.per_triangle.end());
    cache::store(key, std::as_bytes(std::span(cached)));
  }
  if (diameter.measured_area_fraction < 0.9)
    warn(fmt::format("{}: thickness_from_mesh: rays from {:.0f}% of the surface met nothing (an open mesh?); the "
                     "thickness there is the median of the rest", where.str(),
                     100.0 * (1.0 - diameter.measured_area_fraction)));
  std::vector<double> thickness(diameter.per_triangle.size());
  for (std::size_t t = 0; t < thickness.size(); ++t) thickness[t] = diameter.per_triangle[t] / kShapeDiameterOfUnitSlab;
  object.thickness = thickness_grid(transformed(object.mesh, object.world_from_object), thickness,
                                    diameter.median / kShapeDiameterOfUnitSlab);
  object.material->thickness_mm = static_cast<float>(diameter.median / kShapeDiameterOfUnitSlab * scale_mm);
}

SceneObject read_object(const json& j, const JsonLocation& where, const std::string& base_dir, double scale_mm) {
  ParamValues v = read_params(j, {"object", kObjectParams}, where, {"material", "profile", "deform"});
  SceneObject object;
  object.name = v.text("name").empty() ? where.pointer : v.text("name");
  object.mesh = read_geometry(v, read_profile(j, where), where, base_dir);
  if (!v.text("mesh").empty()) object.mesh_file = resolve_path(v.text("mesh"), base_dir);
  object.world_from_object = read_transform(v);
  if (v.text("shape") == "blobs") {
    // The blob field lives in world space about the origin (geometry/blob_field.h).
    for (const char* key : {"translate", "rotate_deg", "scale", "deform", "up_axis"})
      if (j.contains(key)) fail(where.child(key), "not supported for blobs (the field is fixed in world space)");
    object.blob_resolution = v.integer("segments");
  } else {
    check_world_extent(object.mesh, object.world_from_object, where);
    validate_mesh(object.mesh, where.str());
  }
  if (j.contains("deform")) {
    ParamValues d = read_params(j.at("deform"), {"deform", kDeformParams}, where.child("deform"));
    const std::string& type = d.text("type");
    object.deformation.type = type == "bend" ? DeformationType::Bend
                              : type == "melt" ? DeformationType::Melt
                                               : DeformationType::Wave;
    object.deformation.amplitude = static_cast<float>(d.number("amplitude"));
    object.deformation.period_s = static_cast<float>(d.number("period_s"));
    object.deformation.start_s = static_cast<float>(d.number("start_s"));
    if (object.deformation.type == DeformationType::Melt && object.deformation.amplitude >= 1.0f)
      fail(where.child("deform").child("amplitude"), fmt::format("{} must be below 1 for melt (the fraction of height lost)",
                                                                 object.deformation.amplitude));
  }
  object.albedo = v.vec3("albedo");
  if (j.contains("material")) {
    if (j.contains("albedo")) fail(where.child("albedo"), "an object is translucent (material) or opaque (albedo)");
    if (j.at("material") == kFromMesh) read_mesh_material(object, where, scale_mm);
    else object.material = read_material(j.at("material"), where.child("material"), base_dir, scale_mm);
    if (object.material && object.blob_resolution == 0) orient_normals_outward(object.mesh, where.str());
    if (object.material && thickness_from_mesh(j.at("material"))) {
      if (object.material->model == BssrdfModel::Multipole)
        measure_thickness(object, where.child("material"), scale_mm);
      else  // only the multipole model has a thickness: not measured (it costs seconds on a large mesh)
        warn(fmt::format("{}: thickness_from_mesh: only the multipole model uses a thickness (this material's model "
                         "is {}); not measured", where.child("material").str(), to_string(object.material->model)));
    }
    if (object.material && object.material->textured())
      if (const std::string problem = texture_coordinates_problem(object); !problem.empty())
        fail(where.child("material").child(map_key(*object.material->maps)), problem);
  }
  return object;
}

ParamSection method_section(const std::string& name) {
  const methods::MethodInfo* info = methods::find_method(name);
  return {info ? info->name : "method", info ? info->params : std::span<const ParamDecl>{}};
}

void read_method(const json& j, const JsonLocation& where, Scene& scene) {
  require_object(j, where);
  scene.method = read_string(j, "name", std::string(methods::default_method().name), where);
  if (!methods::find_method(scene.method)) {
    std::string known;
    for (const auto* m : methods::method_registry()) known += (known.empty() ? "" : ", ") + std::string(m->name);
    fail(where.child("name"), fmt::format("unknown method '{}'; known: {}", text_excerpt(scene.method), known));
  }
  scene.method_params = read_params(j, method_section(scene.method), where, {"name"});
}

RenderSettings read_render(const json& j, const JsonLocation& where) {
  ParamValues v = read_params(j, {"render", kRenderParams}, where);
  RenderSettings r;
  r.width = v.integer("width");
  r.height = v.integer("height");
  r.frames = v.integer("frames");
  r.seed = static_cast<unsigned>(v.number("seed"));
  r.exposure = static_cast<float>(v.number("exposure"));
  const std::string& op = v.text("tonemap");
  r.tonemap = op == "aces" ? ToneMapOperator::Aces : op == "reinhard" ? ToneMapOperator::Reinhard : ToneMapOperator::Linear;
  r.background = v.vec3("background");
  r.fps = static_cast<float>(v.number("fps"));
  return r;
}

// "--set 'a.b=1'": an assignment as messages name it.
std::string set_name(const std::string& assignment) { return fmt::format("--set '{}'", text_excerpt(assignment)); }

// The value at a --set key path ("a.b.0.c"), created where missing; `pointer` receives its JSON pointer.
json& override_target(json& doc, const std::string& path, const std::string& assignment, std::string& pointer) {
  if (static_cast<std::size_t>(std::count(path.begin(), path.end(), '.')) >= kMaxJsonDepth)
    throw Error(fmt::format("{}: key path deeper than {} levels", set_name(assignment), kMaxJsonDepth));
  json* node = &doc;
  std::istringstream parts(path);
  std::string part;
  std::string parent;  // the key of `node`
  while (std::getline(parts, part, '.')) {
    if (node->is_array()) {
      std::size_t index = 0;
      if (!part.empty() && std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        try {
          index = std::stoul(part);
        } catch (const std::exception&) {
          throw Error(fmt::format("{}: '{}' is not an array index", set_name(assignment), text_excerpt(part)));
        }
      } else {  // an element by its "name" (objects.bunny)
        const auto named = std::find_if(node->begin(), node->end(), [&](const json& element) {
          return element.is_object() && element.value("name", json()) == part;
        });
        if (named == node->end())
          throw Error(fmt::format("{}: '{}' is neither an index nor the name of an element of /{}", set_name(assignment),
                                  text_excerpt(part), text_excerpt(parent)));
        index = static_cast<std::size_t>(named - node->begin());
      }
      if (index >= node->size())
        throw Error(fmt::format("{}: index {} out of range ({} elements)", set_name(assignment), index, node->size()));
      node = &(*node)[index];
      pointer += "/" + std::to_string(index);
    } else {
      if (node->is_null()) *node = json::object();
      if (node->is_string() && parent == "material") *node = json{{"preset", *node}};  // "Marble": a preset's name
      if (!node->is_object())
        throw Error(fmt::format("{}: cannot set '{}' inside {} (not an object)", set_name(assignment),
                                text_excerpt(part), excerpt(*node)));
      node = &(*node)[part];
      pointer += "/" + part;
    }
    parent = part;
  }
  return *node;
}

// "a.b.0.c=value": sets the JSON value at that path; value is JSON, or a bare string when not valid JSON. Returns
// the JSON pointer of the value set.
std::string apply_override(json& doc, const std::string& assignment) {
  auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw Error(fmt::format("{}: expected key.path=value, e.g. method.K=8", set_name(assignment)));
  std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  std::string pointer;
  json& target = override_target(doc, path, assignment, pointer);
  json value = try_parse_json(text, {set_name(assignment), pointer});  // its depth counts from the pointer's
  target = value.is_discarded() ? json(text) : std::move(value);
  return pointer;
}

// A scene whose translucent objects no light reaches renders black: say so (it may be intended while editing).
void warn_if_unlit(const Scene& scene) {
  bool translucent = std::any_of(scene.objects.begin(), scene.objects.end(),
                                 [](const SceneObject& object) { return object.translucent(); });
  if (translucent && scene.lights.empty() && scene.point_lights.empty())
    warn(scene.source + ": translucent objects but no light (lights, environment); the image will be black");
}

// Ray offsets scale with the coordinates (1e-6 of them in volpath, 2e-6 on the GPU: a few float rounding steps);
// a medium whose mean free path is within kOffsetsPerMeanFreePath of the GPU's loses energy at its boundary
// (measured in volpath on a 2 cm ball at the origin with albedo near 1: about 5% at 10 of its offsets per mean free
// path, none measurable at 100; everything at 1). Warned about, naming the object, with what would help.
constexpr double kOffsetsPerMeanFreePath = 32.0;
constexpr double kLargestRelativeOffset = 2e-6;  // the GPU walk's (methods/random_walk/shaders/trace.comp)
constexpr double kLightOnSurfaceOffsets = 4.0;   // a point light this many offsets from a surface is on it
// A translucent object is a medium only inside a closed surface, and a point light inside one lights it only in
// volpath: say so where the image would silently miss the light.
void warn_about_enclosures(const Scene& scene) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    if (!object.translucent() || object.mesh.indices.empty()) continue;
    const TriangleMesh world = transformed(object.mesh, object.world_from_object);
    const std::string what = fmt::format("{}: /objects/{}{}", scene.source, i,
                                         object.name.empty() || object.name[0] == '/' ? "" : fmt::format(" ('{}')", object.name));
    if (const std::size_t open = open_edge_count(world); open > 0)
      warn(fmt::format("{}: a translucent object with an open surface ({} edges border "
                               "one triangle only) encloses no medium: paths that enter it in volpath may never "
                               "leave (dark), while the real-time methods treat its surface as closed",
                       what, open));
    else
      for (const PointLight& light : scene.point_lights) {
        // On the surface (within the ray offsets there: a few float steps of the coordinates) the light is neither
        // inside nor outside for the estimators, which then disagree (volpath lit 45 pixels of a sphere with a
        // light on one of its vertices, the GPU walk none): said, not guessed.
        const glm::dvec3 at(light.position);
        double extent = std::max({std::fabs(at.x), std::fabs(at.y), std::fabs(at.z)});
        for (const glm::vec3& p : world.positions)
          extent = std::max({extent, std::fabs(double(p.x)), std::fabs(double(p.y)), std::fabs(double(p.z))});
        if (distance_to_mesh(world, at) <= kLightOnSurfaceOffsets * kLargestRelativeOffset * extent) {
          warn(fmt::format("{}: the point light at ({}, {}, {}) lies on the surface of this translucent object "
                           "(within the ray offsets there): it is neither inside nor outside it for the estimators, "
                           "which disagree (volpath lights the medium from one side, the GPU walk not at all); move "
                           "it off the surface",
                           what, static_cast<float>(at.x + scene.origin.x), static_cast<float>(at.y + scene.origin.y),
                           static_cast<float>(at.z + scene.origin.z)));
          continue;
        }
        if (encloses(world, at))
          warn(fmt::format("{}: the point light at ({}, {}, {}) is inside this translucent "
                                   "object; only the volpath reference renders light from inside a medium (the "
                                   "real-time methods and the bssrdf reference light surfaces from outside, where "
                                   "it lights nothing)",
                           what, static_cast<float>(light.position.x + scene.origin.x),
                           static_cast<float>(light.position.y + scene.origin.y),
                           static_cast<float>(light.position.z + scene.origin.z)));
      }
  }
}

// The media too dense for the offsets at their coordinates (kOffsetsPerMeanFreePath), one warning each.
void warn_about_unrepresentable_media(const Scene& scene) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    if (!object.material || object.mesh.positions.empty()) continue;
    double largest = 0.0;
    for (const glm::vec3& p : transformed(object.mesh, object.world_from_object).positions)
      largest = std::max({largest, std::fabs(double(p.x)), std::fabs(double(p.y)), std::fabs(double(p.z))});
    const glm::vec3 sigma_t = object.material->sigma_t() * object.material->field.max_multiplier();
    const double mfp_mm = 1.0 / std::max({double(sigma_t.x), double(sigma_t.y), double(sigma_t.z), 1e-30});
    const double offset_mm = kLargestRelativeOffset * largest * scene.scale_mm;
    if (mfp_mm >= kOffsetsPerMeanFreePath * offset_mm) continue;
    warn(fmt::format("{}: /objects/{}: the shortest mean free path of its medium, {:.3g} mm, is only {:.3g} ray offsets "
                     "long at the object's coordinates (offsets are {:g} of them: {:.3g} mm here): volpath and "
                     "random-walk lose light at its boundary (about 5% at 5 offsets, all of it at 0.5); a "
                     "smaller scale_mm, the object nearer the origin, or a less dense medium keeps them exact",
                     scene.source, i, mfp_mm, mfp_mm / offset_mm, kLargestRelativeOffset, offset_mm));
  }
}

// A JSON array of three finite numbers, as doubles.
std::optional<glm::dvec3> json_point(const json& value) {
  if (!value.is_array() || value.size() != 3) return std::nullopt;
  glm::dvec3 p;
  for (int i = 0; i < 3; ++i) {
    if (!value[static_cast<std::size_t>(i)].is_number()) return std::nullopt;
    p[i] = value[static_cast<std::size_t>(i)].get<double>();
    if (!std::isfinite(p[i])) return std::nullopt;
  }
  return p;
}

// Scene::origin: when the camera's target lies more than kFarFromOrigin times its distance from the eye away from the
// file's origin, every position the file gives (the camera's eye and target, point and spot lights, objects'
// translations) is moved by minus the target, in double precision, before it becomes float; returns the target
// (zero otherwise: the file's numbers are kept as they are). Not with blobs, whose field lies about the file's
// origin, nor when a position is malformed (the reader then names it).
glm::dvec3 move_origin_to_the_view(json& doc) {
  if (!doc.is_object() || !doc.contains("camera") || !doc["camera"].is_object()) return glm::dvec3(0.0);
  json& camera = doc["camera"];
  const std::optional<glm::dvec3> target = json_point(camera.value("target", json::array({0, 0, 0})));
  const std::optional<glm::dvec3> eye = json_point(camera.value("eye", json::array({0, 0, 5})));
  if (!target || !eye) return glm::dvec3(0.0);
  const double distance = glm::length(*eye - *target);
  if (!(glm::length(*target) > kFarFromOrigin * distance)) return glm::dvec3(0.0);
  std::vector<json*> positions = {&camera["eye"], &camera["target"]};
  camera["eye"] = json::array({eye->x, eye->y, eye->z});
  camera["target"] = json::array({target->x, target->y, target->z});
  if (doc.contains("lights")) {
    if (!doc["lights"].is_array()) return glm::dvec3(0.0);
    for (json& light : doc["lights"])
      if (light.is_object() && light.contains("position")) positions.push_back(&light["position"]);
  }
  if (!doc.contains("objects") || !doc["objects"].is_array()) return glm::dvec3(0.0);
  for (json& object : doc["objects"]) {
    if (!object.is_object() || object.value("shape", json()) == "blobs") return glm::dvec3(0.0);
    if (!object.contains("translate")) object["translate"] = json::array({0, 0, 0});
    positions.push_back(&object["translate"]);
  }
  for (const json* p : positions)
    if (!json_point(*p)) return glm::dvec3(0.0);
  for (json* p : positions) {
    const glm::dvec3 moved = *json_point(*p) - *target;
    *p = json::array({moved.x, moved.y, moved.z});
  }
  return *target;
}

}  // namespace

Scene parse_scene(const std::string& json_text, const std::string& source, const std::string& base_dir,
                  const std::vector<std::string>& overrides) {
  json doc = parse_json(json_text, {source, ""});
  std::vector<JsonOverride> applied;  // errors at or under a value set by --set name the assignment
  for (const std::string& assignment : overrides) applied.push_back({apply_override(doc, assignment), assignment});
  JsonLocation root{source, "", &applied};
  ParamValues top = read_params(doc, {"scene", kSceneParams}, root, {"camera", "lights", "environment", "objects", "method", "render", "denoise"});
  Scene scene;
  scene.origin = move_origin_to_the_view(doc);
  scene.source = source;
  scene.scale_mm = static_cast<float>(top.number("scale_mm"));
  scene.camera = read_camera(doc.value("camera", json::object()), root.child("camera"));
  const json lights = doc.value("lights", json::array());
  if (!lights.is_array()) fail(root.child("lights"), "expected an array of lights");
  for (std::size_t i = 0; i < lights.size(); ++i) read_light(lights[i], root.child("lights").child(i), scene);
  if (doc.contains("environment")) read_environment(doc["environment"], root.child("environment"), base_dir, scene);
  const json objects = doc.value("objects", json::array());
  if (!objects.is_array() || objects.empty()) fail(root.child("objects"), "expected a non-empty array of objects");
  for (std::size_t i = 0; i < objects.size(); ++i)
    scene.objects.push_back(read_object(objects[i], root.child("objects").child(i), base_dir, scene.scale_mm));
  warn_about_gltf_mean_free_paths(objects, scene);
  warn_about_unrepresentable_media(scene);
  read_method(doc.value("method", json::object()), root.child("method"), scene);
  // A method that evaluates the diffusion models needs sigma_a and sigma_s' positive; one that estimates volpath
  // renders a pure scatterer or a band that only absorbs.
  if (const methods::MethodInfo* info = methods::find_method(scene.method); info && !info->estimates_volpath)
    for (std::size_t i = 0; i < scene.objects.size(); ++i)
      if (scene.objects[i].material)
        validate_diffusion_medium(*scene.objects[i].material, root.child("objects").child(i).child("material").str());
  scene.render = read_render(doc.value("render", json::object()), root.child("render"));
  scene.denoise = read_params(doc.value("denoise", json::object()), {"denoise", denoise::kDenoiseParams}, root.child("denoise"));
  warn_if_unlit(scene);
  warn_about_enclosures(scene);
  return scene;
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  check_file_path(path);
  // A directory opens as an empty stream on Linux: say what it is rather than report empty JSON.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error(fmt::format("{}: is a directory; give a scene file (JSON)", path));
  require_regular_file(path);
  std::ifstream file(path);
  if (!file) throw Error(fmt::format("{}: cannot open scene file", path));
  std::stringstream text;
  text << file.rdbuf();
  std::string base_dir = std::filesystem::path(path).parent_path().string();
  return parse_scene(text.str(), path, base_dir.empty() ? "." : base_dir, overrides);
}

bool has_material_maps(const Scene& scene) {
  return std::any_of(scene.objects.begin(), scene.objects.end(),
                     [](const SceneObject& o) { return o.material && o.material->textured(); });
}

void check_material_maps(const Scene& scene) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    if (!object.material || !object.material->maps) continue;
    const Material& m = *object.material;
    const MaterialMaps& maps = *m.maps;
    const std::string where = fmt::format("{}: /objects/{}/material", scene.source, i);
    const char* key = map_key(maps);
    if (const std::string problem = texture_coordinates_problem(object); !problem.empty())
      throw Error(fmt::format("{}/{}: {}", where, key, problem));
    if (const std::string problem = table_model_maps_problem(m.model, key); !problem.empty())
      throw Error(fmt::format("{}/model: {}", where, problem));
    if (m.g != maps.made_with_g || m.eta != maps.made_with_eta || m.model != maps.made_with_model ||
        m.sigma_a != maps.made_with_sigma_a || m.sigma_s != maps.made_with_sigma_s)
      throw Error(fmt::format("{}: the coefficients, g, eta and model of a textured material are those its {} was "
                              "made with (its texels are inverted at load); change them in the scene file", where, key));
  }
}

std::vector<std::string> scene_input_files(const Scene& scene) {
  std::vector<std::string> files = {scene.source};
  if (scene.environment) files.push_back(scene.environment->file);
  for (const SceneObject& object : scene.objects) {
    if (!object.mesh_file.empty()) {
      files.push_back(object.mesh_file);
      const std::string extension = lowercase_extension(object.mesh_file);
      if (extension == ".gltf" || extension == ".glb")
        for (std::string& file : gltf_referenced_files(object.mesh_file)) files.push_back(std::move(file));
    }
    if (object.material && object.material->maps) {
      for (const std::string* file : {&object.material->maps->albedo_file, &object.material->maps->mfp_file})
        if (!file->empty()) files.push_back(*file);
    }
    if (object.material && object.material->field.volume) {
      files.push_back(object.material->field.volume->source);
      files.push_back(object.material->field.volume->data_file);
    }
  }
  return files;
}

std::vector<ParamSection> scene_param_sections() {
  std::vector<ParamSection> sections = {{"scene", kSceneParams},       {"camera", kCameraParams},
                                        {"lights[]", kLightParams},    {"environment", kEnvironmentParams},
                                        {"objects[]", kObjectParams},          {"objects[].deform", kDeformParams},
                                        {"objects[].material", kMaterialParams}, {"objects[].material.field", kFieldParams},
                                        {"objects[].material.principled", kPrincipledParams},
                                        {"objects[].material.openpbr", kOpenPbrParams}, {"render", kRenderParams},
                                        {"denoise", denoise::kDenoiseParams}};
  for (const auto* m : methods::method_registry()) sections.push_back({m->name, m->params});
  return sections;
}

glm::mat4 Camera::view_from_world() const { return glm::lookAt(eye, target, up); }

glm::mat4 Camera::clip_from_view(float aspect, float z_near, float z_far) const {
  return glm::perspective(glm::radians(fov_y_deg), aspect, z_near, z_far);
}

}  // namespace lucent
