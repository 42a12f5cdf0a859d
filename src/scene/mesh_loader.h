// mesh_loader.h: load_mesh (lucent/mesh.h) with the texture coordinates of another set than 0, for a glTF texture
// that reads TEXCOORD_<n> (scene/gltf_material.h, GltfTextureCoordinates).
#pragma once
#include <string>

#include "lucent/mesh.h"

namespace lucent {

// load_mesh with the texture coordinates of channel `uv_set` (glTF's TEXCOORD_<uv_set>) instead of channel 0:
// the same vertices, in the same order (the importer joins vertices equal in every channel).
TriangleMesh load_mesh_with_uv_set(const std::string& path, unsigned uv_set);

}  // namespace lucent
