// scene_atlas_cache.h: the scene atlas through the precompute cache (src/cache/precompute_cache.h): built once per
// set of translucent meshes, transforms and options, then read back (kind "texture-atlas", key atlas_cache_key).
#pragma once
#include <functional>

#include "texture_space/scene_atlas.h"

namespace lucent::texture_space {

struct CachedSceneAtlas {
  SceneAtlas atlas;
  bool from_cache = false;  // read from the cache, not built (its metrics.build_ms is the original build's)
};

// The cached atlas when the key matches, else build_scene_atlas's, then stored. `progress` (may be empty) is
// called with 0 before and 1 after. Errors as build_scene_atlas (blob surfaces refused before the cache is
// looked at); a damaged entry is one warning line and a rebuild (lucent::cache); a disabled cache
// (cache::set_enabled(false), --no-cache) builds and writes nothing.
CachedSceneAtlas load_or_build_scene_atlas(const Scene& scene, const AtlasOptions& options,
                                           const std::function<void(double)>& progress = {});

}  // namespace lucent::texture_space
