// scene_atlas.h: one atlas for all translucent objects of a scene, and the scene prepared for a texture-space
// method (every translucent mesh carrying atlas texture coordinates).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "cache/precompute_cache.h"
#include "lucent/scene.h"
#include "texture_space/atlas.h"

namespace lucent::texture_space {

struct SceneAtlas {
  Atlas atlas;                        // objects[k] belongs to scene object object_index[k]
  std::vector<std::size_t> object_index;
  bool own_uvs = false;               // the single translucent mesh's own texture coordinates are the atlas
  std::string own_uv_problem;         // why its own coordinates were not used (empty when there were none to test)
};

// The atlas of the scene's translucent objects, in scene order. A single translucent object whose own texture
// coordinates pass uv_problem keeps them (metrics from uv_metrics); otherwise charts are built for all of them
// together (own coordinates of several objects cannot share one texture). Throws lucent::Error
// "<scene>: object '<name>': ..." for a blob surface (no parameterisation survives its re-extraction) and
// "<scene>: no translucent object" when there is nothing to lay out.
SceneAtlas build_scene_atlas(const Scene& scene, const AtlasOptions& options);

// The scene with each translucent object's mesh replaced by its atlas mesh (same positions and normals per
// corner, vertices split at seams, uvs set); deformations keep working on the rest pose.
Scene with_atlas_meshes(const Scene& scene, const SceneAtlas& atlas);

// The scene atlas's key in the precompute cache (kind "texture-atlas"): the encoding and builder versions, the
// options, and each translucent object's index, mesh (with its own texture coordinates) and transform. Throws as
// build_scene_atlas does for blob surfaces and scenes without a translucent object.
cache::Key atlas_cache_key(const Scene& scene, const AtlasOptions& options);

}  // namespace lucent::texture_space
