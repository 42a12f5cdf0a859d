// scene_atlas_cache.cpp: see scene_atlas_cache.h.
#include "texture_space/scene_atlas_cache.h"

#include <fmt/format.h>

#include "lucent/warning.h"
#include "lucent/error.h"
#include "texture_space/atlas_encoding.h"

namespace lucent::texture_space {

CachedSceneAtlas load_or_build_scene_atlas(const Scene& scene, const AtlasOptions& options,
                                           const std::function<void(double)>& progress) {
  if (progress) progress(0.0);
  const cache::Key key = atlas_cache_key(scene, options);
  CachedSceneAtlas out;
  if (std::optional<std::vector<std::byte>> bytes = cache::load(key)) {
    try {
      out.atlas = decode_scene_atlas(*bytes);
      out.from_cache = true;
    } catch (const Error& e) {  // a checksummed entry that does not decode: a format change without a version bump
      warn(fmt::format("{}: {}; rebuilding", cache::entry_path(key).string(), e.what()));
    }
  }
  if (!out.from_cache) {
    out.atlas = build_scene_atlas(scene, options);
    cache::store(key, encode_scene_atlas(out.atlas));
  }
  if (progress) progress(1.0);
  return out;
}

}  // namespace lucent::texture_space
