// scene_writer.cpp: Scene -> scene JSON (the keys scene_loader.cpp reads) and mesh files beside it.
#include "lucent/scene_writer.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "denoise/denoise_params.h"
#include "io/base64.h"
#include "lucent/error.h"
#include "lucent/medium_vdb.h"
#include "lucent/output_file.h"
#include "methods/method_info.h"
#include "scene/gltf_material.h"

namespace lucent {
namespace {

using nlohmann::json;

json vec(glm::vec3 v) { return json::array({v.x, v.y, v.z}); }
json vec(glm::vec2 v) { return json::array({v.x, v.y}); }
// A position in the file's coordinates: the Scene's plus its origin (Scene::origin), in double.
json at(glm::vec3 p, const glm::dvec3& origin) {
  const glm::dvec3 q = glm::dvec3(p) + origin;
  return json::array({q.x, q.y, q.z});
}

// The loader's transform: translate, then rotate about z, y, x (so x applies first), then scale.
glm::mat4 compose(const ObjectTransform& t) {
  glm::vec3 r = glm::radians(t.rotate_deg);
  glm::mat4 m = glm::translate(glm::mat4(1.0f), t.translate);
  m = glm::rotate(m, r.z, glm::vec3(0, 0, 1));
  m = glm::rotate(m, r.y, glm::vec3(0, 1, 0));
  m = glm::rotate(m, r.x, glm::vec3(1, 0, 0));
  return glm::scale(m, glm::vec3(t.scale));
}

float max_abs_difference(const glm::mat4& a, const glm::mat4& b) {
  float d = 0.0f;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) d = std::max(d, std::abs(a[c][r] - b[c][r]));
  return d;
}

// Angles and scales typed by people are round: 70 deg comes back as 69.99999; snap to 1e-4 when that is closer.
float snapped(double x) { return static_cast<float>(std::round(x * 1e4) / 1e4); }

json light_json(const DirectionalLight& light) {
  return {{"type", "directional"}, {"direction", vec(light.direction)}, {"radiance", vec(light.radiance)}};
}

json light_json(const PointLight& light, const glm::dvec3& origin) {
  json j = {{"type", light.spot ? "spot" : "point"}, {"position", at(light.position, origin)},
            {"intensity", vec(light.intensity)}};
  if (light.spot) {
    j["direction"] = vec(light.direction);
    j["inner_deg"] = light.inner_deg;
    j["outer_deg"] = light.outer_deg;
  }
  return j;
}

// A preset by name when the coefficients are the preset's, else explicit coefficients (which lose the name).
json material_json(const Material& m) {
  json j;
  const MaterialPreset* preset = find_material_preset(m.name);
  Material from_preset = preset ? material_from_preset(*preset) : Material{};
  if (preset && from_preset.name == m.name && from_preset.sigma_a == m.sigma_a && from_preset.sigma_s == m.sigma_s &&
      from_preset.g == m.g) {
    j["preset"] = m.name;
  } else {
    j["sigma_a"] = vec(m.sigma_a);
    j["sigma_s"] = vec(m.sigma_s);
    j["g"] = vec(m.g);
  }
  j["eta"] = m.eta;
  j["model"] = std::string(to_string(m.model));
  if (m.thickness_mm > 0.0f) j["thickness_mm"] = m.thickness_mm;
  if (m.maps) {  // the coefficients written above are the maps' mean; the maps themselves by absolute path
    const MaterialMaps& maps = *m.maps;
    if (!maps.albedo_file.empty()) {
      // An albedo map needs the artist form: its mean free path (the map's alpha replaces the coefficients').
      j.erase("preset"), j.erase("sigma_a"), j.erase("sigma_s");
      j["mfp_mm"] = vec(maps.base_mfp_mm);
      j["albedo_map"] = std::filesystem::absolute(maps.albedo_file).string();
    } else {
      j.erase("preset");
      j["sigma_a"] = vec((1.0f - maps.base_alpha) / maps.base_mfp_mm);
      j["sigma_s"] = vec(maps.base_alpha / maps.base_mfp_mm);
      j["g"] = vec(m.g);
    }
    if (!maps.mfp_file.empty()) j["mfp_map"] = std::filesystem::absolute(maps.mfp_file).string();
  }
  if (m.field.heterogeneous()) {
    json field = {{"type", std::string(to_string(m.field.type))}};
    if (m.field.type == MediumFieldType::Volume) {
      // The file the volume was read from, absolute, so the saved scene finds it from any folder.
      field["file"] = std::filesystem::absolute(m.field.volume ? m.field.volume->source : m.field.file).string();
      if (const VdbField* vdb = vdb_field_of(m.field.volume)) {  // read from an OpenVDB file (lucent/medium_vdb.h)
        field["type"] = "vdb";
        field["grid"] = vdb->grid;
        field["density_scale"] = vdb->density_scale;
        field["transform"] = std::string(to_string(vdb->transform));
      }
    } else {
      field["scale_mm"] = m.field.scale_mm;
      field["contrast"] = m.field.contrast;
    }
    j["field"] = field;
  }
  return j;
}

json deformation_json(const Deformation& d) {
  const char* type = d.type == DeformationType::Bend ? "bend" : d.type == DeformationType::Melt ? "melt" : "wave";
  return {{"type", type}, {"amplitude", d.amplitude}, {"period_s", d.period_s}, {"start_s", d.start_s}};
}

// An object whose albedo map is its glTF mesh's base colour texture ("material": "from_mesh"; the map's file is
// "<mesh file>#<pointer>", scene/gltf_material.cpp). A textured material cannot be edited (check_material_maps), so
// the glTF material is still the object's.
bool takes_gltf_texture(const SceneObject& object) {
  if (!object.material || !object.material->maps || object.mesh_file.empty()) return false;
  return object.material->maps->albedo_file.rfind(object.mesh_file + "#", 0) == 0;
}

json object_json(const SceneObject& object, std::size_t index, const std::vector<std::string>& mesh_files,
                 const glm::dvec3& origin) {
  json j = {{"name", object.name}};
  if (object.blob_resolution > 0) {
    j["shape"] = "blobs";
    j["segments"] = object.blob_resolution;
  } else {
    if (index >= mesh_files.size() || mesh_files[index].empty())
      throw Error(fmt::format("save scene: object {} ('{}') has no mesh file to reference", index, object.name));
    j["mesh"] = mesh_files[index];
    ObjectTransform t = decompose_object_transform(object.world_from_object, fmt::format("object '{}'", object.name));
    j["translate"] = at(t.translate, origin);
    j["rotate_deg"] = vec(t.rotate_deg);
    j["scale"] = t.scale;
    if (object.deformation.type != DeformationType::None) j["deform"] = deformation_json(object.deformation);
  }
  if (object.material) {
    j["material"] = material_json(*object.material);
    if (!object.thickness.empty()) {  // measured per point: measured again when the file is read
      j["material"].erase("thickness_mm");
      j["material"]["thickness_from_mesh"] = true;
    }
  }
  else j["albedo"] = vec(object.albedo);
  if (takes_gltf_texture(object)) {  // the texture lives in the glTF: the object takes the file's material again
    j["mesh"] = std::filesystem::absolute(object.mesh_file).string();
    j["material"] = "from_mesh";
  }
  return j;
}

json param_json(const ParamDecl& decl, const ParamValue& value) {
  switch (decl.type) {
    case ParamType::Int: return static_cast<std::int64_t>(std::llround(std::get<double>(value)));
    case ParamType::Float: return std::get<double>(value);
    case ParamType::Bool: return std::get<bool>(value);
    case ParamType::Enum:
    case ParamType::String: return std::get<std::string>(value);
    case ParamType::Vec2: return vec(glm::vec2(std::get<glm::vec3>(value)));
    case ParamType::Vec3: return vec(std::get<glm::vec3>(value));
    case ParamType::Vec3List: {
      json list = json::array();
      for (const glm::vec3& v : std::get<std::vector<glm::vec3>>(value)) list.push_back(vec(v));
      return list;
    }
  }
  return nullptr;
}

json method_json(const Scene& scene) {
  json j = {{"name", scene.method}};
  const methods::MethodInfo* info = methods::find_method(scene.method);
  if (!info) throw Error(fmt::format("save scene: unknown method '{}'", scene.method));
  for (const ParamDecl& decl : info->params)
    if (scene.method_params.has(decl.name))
      j[std::string(decl.name)] = param_json(decl, scene.method_params.all().at(std::string(decl.name)));
  return j;
}

// The denoising stage's values, written when it is enabled (a scene without the object has it off).
json denoise_json(const Scene& scene) {
  json j = json::object();
  for (const ParamDecl& decl : denoise::kDenoiseParams)
    if (scene.denoise.has(decl.name))
      j[std::string(decl.name)] = param_json(decl, scene.denoise.all().at(std::string(decl.name)));
  return j;
}

json render_json(const RenderSettings& r) {
  const char* tonemap = r.tonemap == ToneMapOperator::Aces       ? "aces"
                        : r.tonemap == ToneMapOperator::Reinhard ? "reinhard"
                                                                 : "linear";
  return {{"width", r.width},       {"height", r.height},     {"frames", r.frames},
          {"seed", r.seed},         {"exposure", r.exposure}, {"tonemap", tonemap},
          {"background", vec(r.background)}, {"fps", r.fps}};
}

std::string mesh_file_name(std::size_t index, const std::string& name) {
  std::string safe;
  for (char c : name) safe += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  return fmt::format("{}_{}.gltf", index, safe);
}

}  // namespace

ObjectTransform decompose_object_transform(const glm::mat4& m, const std::string& what) {
  glm::vec3 column[3] = {glm::vec3(m[0]), glm::vec3(m[1]), glm::vec3(m[2])};
  double scale = glm::length(column[0]);
  if (!(scale > 0.0)) throw Error(what + ": transform has zero scale");
  // R = Rz(c) Ry(b) Rx(a); R(row, col) = m[col][row] / scale.
  auto R = [&](int row, int col) { return static_cast<double>(m[col][row]) / scale; };
  double sin_b = std::clamp(-R(2, 0), -1.0, 1.0);
  double a, b = std::asin(sin_b), c;
  if (std::abs(std::cos(b)) > 1e-6) {
    a = std::atan2(R(2, 1), R(2, 2));
    c = std::atan2(R(1, 0), R(0, 0));
  } else {  // gimbal lock: only a - c (or a + c) is defined; put it all in a
    a = std::atan2(-R(1, 2), R(1, 1));
    c = 0.0;
  }
  ObjectTransform raw{glm::vec3(m[3]),
                      glm::vec3(glm::degrees(a), glm::degrees(b), glm::degrees(c)), static_cast<float>(scale)};
  ObjectTransform round{raw.translate,
                        glm::vec3(snapped(glm::degrees(a)), snapped(glm::degrees(b)), snapped(glm::degrees(c))),
                        snapped(scale)};
  float raw_error = max_abs_difference(compose(raw), m), round_error = max_abs_difference(compose(round), m);
  ObjectTransform best = round_error <= raw_error ? round : raw;
  float largest = 1.0f;
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) largest = std::max(largest, std::abs(m[col][row]));
  if (std::min(raw_error, round_error) > 1e-4f * largest)
    throw Error(what + ": transform is not translate * rotate * uniform scale; the scene format cannot express it");
  return best;
}

json scene_to_json(const Scene& scene, const std::vector<std::string>& mesh_files) {
  json j;
  j["comment"] = fmt::format("written by lucent from {}", scene.source);
  j["scale_mm"] = scene.scale_mm;
  j["camera"] = {{"eye", at(scene.camera.eye, scene.origin)}, {"target", at(scene.camera.target, scene.origin)},
                 {"up", vec(scene.camera.up)}, {"fov_y_deg", scene.camera.fov_y_deg}};
  json lights = json::array();
  for (const DirectionalLight& light : scene.lights) {
    if (!light.specular) {
      if (scene.environment) continue;  // sampled from the environment map: the loader samples it again
      throw Error("save scene: a directional light without specular reflection exists only for environment maps");
    }
    lights.push_back(light_json(light));
  }
  for (const PointLight& light : scene.point_lights) lights.push_back(light_json(light, scene.origin));
  j["lights"] = lights;
  if (scene.environment)
    j["environment"] = {{"file", scene.environment->file}, {"lights", scene.environment->light_count},
                        {"intensity", scene.environment->intensity}, {"background", scene.environment->background}};
  json objects = json::array();
  for (std::size_t i = 0; i < scene.objects.size(); ++i) objects.push_back(object_json(scene.objects[i], i, mesh_files, scene.origin));
  j["objects"] = objects;
  j["method"] = method_json(scene);
  j["render"] = render_json(scene.render);
  if (denoise::denoise_settings(scene.denoise).enabled) j["denoise"] = denoise_json(scene);
  return j;
}

json scene_to_json(const Scene& scene) {
  std::vector<std::string> files;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) files.push_back(mesh_file_name(i, scene.objects[i].name));
  return scene_to_json(scene, files);
}

namespace {

template <class T>
void append_bytes(std::vector<std::uint8_t>& buffer, const std::vector<T>& values) {
  const auto* begin = reinterpret_cast<const std::uint8_t*>(values.data());
  buffer.insert(buffer.end(), begin, begin + values.size() * sizeof(T));
}

}  // namespace

void write_gltf(const std::string& path, const TriangleMesh& mesh, const json& material) {
  static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");
  std::vector<std::uint8_t> buffer;
  append_bytes(buffer, mesh.positions);
  append_bytes(buffer, mesh.normals);
  append_bytes(buffer, mesh.indices);
  // glTF's texture origin is the top left of the image, lucent's (OpenGL's) the bottom left.
  std::vector<glm::vec2> texcoords;
  for (glm::vec2 uv : mesh.uvs) texcoords.emplace_back(uv.x, 1.0f - uv.y);
  append_bytes(buffer, texcoords);
  std::size_t vertex_bytes = mesh.positions.size() * sizeof(glm::vec3);
  std::size_t index_bytes = mesh.indices.size() * sizeof(std::uint32_t);
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  constexpr int kFloat = 5126, kUnsignedInt = 5125, kArrayBuffer = 34962, kElementArrayBuffer = 34963;
  json gltf = {
      {"asset", {{"version", "2.0"}, {"generator", "lucent scene_writer"}}},
      {"scene", 0},
      {"scenes", json::array({{{"nodes", json::array({0})}}})},
      {"nodes", json::array({{{"mesh", 0}}})},
      {"meshes", json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}},
                                                            {"indices", 2}, {"mode", 4}}})}}})},
      {"buffers", json::array({{{"byteLength", buffer.size()},
                                {"uri", "data:application/octet-stream;base64," + base64(buffer)}}})},
      {"bufferViews", json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", vertex_bytes}, {"target", kArrayBuffer}},
                                   {{"buffer", 0}, {"byteOffset", vertex_bytes}, {"byteLength", vertex_bytes}, {"target", kArrayBuffer}},
                                   {{"buffer", 0}, {"byteOffset", 2 * vertex_bytes},
                                    {"byteLength", index_bytes}, {"target", kElementArrayBuffer}}})},
      {"accessors", json::array({{{"bufferView", 0}, {"componentType", kFloat}, {"count", mesh.positions.size()},
                                  {"type", "VEC3"}, {"min", vec(lo)}, {"max", vec(hi)}},
                                 {{"bufferView", 1}, {"componentType", kFloat}, {"count", mesh.normals.size()}, {"type", "VEC3"}},
                                 {{"bufferView", 2}, {"componentType", kUnsignedInt}, {"count", mesh.indices.size()},
                                  {"type", "SCALAR"}}})}};
  if (!texcoords.empty()) {
    gltf["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 3;
    gltf["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 2 * vertex_bytes + index_bytes},
                                   {"byteLength", texcoords.size() * sizeof(glm::vec2)}, {"target", kArrayBuffer}});
    gltf["accessors"].push_back(
        {{"bufferView", 3}, {"componentType", kFloat}, {"count", texcoords.size()}, {"type", "VEC2"}});
  }
  if (!material.is_null()) {
    gltf["materials"] = json::array({material});
    gltf["meshes"][0]["primitives"][0]["material"] = 0;
    if (const std::vector<std::string> used = gltf_material_extensions(material); !used.empty())
      gltf["extensionsUsed"] = used;
  }
  write_file(path, gltf.dump() + "\n");
}

json object_gltf_material(const SceneObject& object) {
  if (!object.material) return gltf_opaque_material_json(object.albedo);
  glm::vec3 lo(HUGE_VALF), hi(-HUGE_VALF);
  for (const glm::vec3& p : object.mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 size = glm::max(hi - lo, glm::vec3(0.0f));
  return gltf_material_json(*object.material, std::min({size.x, size.y, size.z}));
}

void save_scene(const Scene& scene, const std::string& path) {
  namespace fs = std::filesystem;
  fs::path scene_path = path, dir = scene_path.parent_path();
  fs::path mesh_dir_name = scene_path.stem().string() + ".meshes";
  // Every file is checked before the first is written: none may be a file the scene was read from.
  std::vector<OutputPath> outputs = {{path, "scene", {".json"}}};
  std::vector<std::string> mesh_files(scene.objects.size());
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    if (scene.objects[i].blob_resolution > 0) continue;
    fs::path relative = mesh_dir_name / mesh_file_name(i, scene.objects[i].name);
    mesh_files[i] = relative.generic_string();
    outputs.push_back({(dir / relative).string(), "scene mesh", {".gltf"}});
  }
  check_outputs(outputs, scene_input_files(scene));
  const OutputLock lock(outputs);
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (!mesh_files[i].empty())
      write_gltf((dir / mesh_files[i]).string(), scene.objects[i].mesh, object_gltf_material(scene.objects[i]));
  json j = scene_to_json(scene, mesh_files);
  if (scene.environment) {
    fs::path base = fs::absolute(dir.empty() ? fs::path(".") : dir).lexically_normal();
    fs::path map = fs::absolute(scene.environment->file).lexically_normal();
    j["environment"]["file"] = map.lexically_relative(base).generic_string();
  }
  write_file(path, j.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
}

}  // namespace lucent
