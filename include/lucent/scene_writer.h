// scene_writer.h: a Scene back to scene JSON that load_scene reads into an equal scene ("save scene as" in the
// viewer, so a view found interactively re-renders from the CLI exactly).
//
//   lucent::save_scene(renderer.scene(), "out/my_view.json");   // + out/my_view.meshes/*.gltf
//   lucent::Scene same = lucent::load_scene("out/my_view.json");
//
// A Scene keeps triangle meshes, not the shape parameters or the mesh file they were made from, so object
// geometry is written as glTF files (exact float positions and normals) beside the scene, each with the object's
// material as a glTF material (docs/materials.md; the scene file keeps the material too); the object's
// transform is written as translate, rotate_deg and scale. Environment-map lights (Scene::lights appended by
// the loader, specular off) are written as the `environment` they came from.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lucent/scene.h"

namespace lucent {

// The scene as JSON. `mesh_files[i]` is written as object i's "mesh" (paths as the scene file should read them);
// blob objects need none. Throws lucent::Error when a mesh object has no file or the scene holds something the
// format cannot express (a non-uniform or sheared transform, a directional light with specular off outside an
// environment).
nlohmann::json scene_to_json(const Scene& scene, const std::vector<std::string>& mesh_files);
// The same with mesh files "<index>_<name>.gltf" (relative), for scenes whose meshes are written by the caller.
nlohmann::json scene_to_json(const Scene& scene);

// Writes `path` (pretty-printed JSON) and each object's mesh as <path without .json>.meshes/<index>_<name>.gltf.
// The environment map is referenced relative to the new file. Throws lucent::Error naming the file it cannot write.
void save_scene(const Scene& scene, const std::string& path);

// The whole scene as one glTF 2.0 file for other tools (Blender, glTF viewers; docs/materials.md, "Whole-scene
// export"): every object a named node and mesh under a node scaling scene units to metres (scale_mm / 1000), its
// material as gltf_material_json writes it (KHR_materials_transmission, _volume, _volume_scatter, _ior, the exact
// coefficients in extras.lucent), the camera a perspective camera node, the lights KHR_lights_punctual (lux and
// candela at 683 lm/W). A .glb `path` gets the binary container, a .gltf one its buffer embedded (base64). Animated
// objects are written as they are at time 0. Throws lucent::Error naming the file it cannot write.
void save_scene_gltf(const Scene& scene, const std::string& path);
// save_scene_gltf for a .gltf or .glb `path`, save_scene for a .json one; another extension is a lucent::Error.
void save_scene_as(const Scene& scene, const std::string& path);
// The bytes save_scene_gltf writes (`path` chooses the container and names the scene).
std::string scene_gltf(const Scene& scene, const std::string& path);

// A triangle mesh as glTF 2.0 with its buffer embedded (base64): load_mesh reads back the same float positions
// and normals, bit for bit (assimp may merge identical vertices), and the texture coordinates as TEXCOORD_0
// (stored as (u, 1 - v), glTF's origin being the image's top left: within an ulp of 1 after reading back). Text formats would not: assimp parses decimal
// numbers to within an ulp, and its binary PLY reader asserts on triangle lists (assimp 5.2).
// `material`: a glTF material object (src/scene/gltf_material.h) that the mesh's primitive uses, or null for none.
void write_gltf(const std::string& path, const TriangleMesh& mesh, const nlohmann::json& material = nullptr);
// The glTF material of an object (docs/materials.md, "Export"): a translucent material with
// KHR_materials_transmission, _volume, _volume_scatter, _ior and its exact coefficients in extras.lucent, or the
// opaque albedo as the base colour.
nlohmann::json object_gltf_material(const SceneObject& object);

// translate, rotate_deg (x, then y, then z, as the loader applies them) and scale of a transform the loader can
// build; throws lucent::Error naming `what` otherwise.
struct ObjectTransform {
  glm::vec3 translate{0.0f};
  glm::vec3 rotate_deg{0.0f};
  float scale = 1.0f;
};
ObjectTransform decompose_object_transform(const glm::mat4& world_from_object, const std::string& what);

}  // namespace lucent
