// atlas_encoding.h: a scene atlas as bytes, for the precompute cache: every field of SceneAtlas (each object's
// atlas mesh with its texture coordinates, source vertices and chart ids, the metrics, the size, the object
// indices and the own-coordinates outcome), little-endian as the machine stores it (the cache checks that at
// compile time). Versioned by kSceneAtlasEncodingVersion, part of the cache key.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "texture_space/scene_atlas.h"

namespace lucent::texture_space {

// Bumped whenever the byte layout below changes.
inline constexpr std::uint32_t kSceneAtlasEncodingVersion = 1;

std::vector<std::byte> encode_scene_atlas(const SceneAtlas& atlas);

// The atlas encode_scene_atlas wrote. Throws lucent::Error "scene atlas: ..." when the bytes are not one (cut
// short, trailing bytes, counts that do not fit, indices out of range): the cache checksums its entries, so this
// is a bug or a format change without a version bump, never trusted.
SceneAtlas decode_scene_atlas(std::span<const std::byte> bytes);

}  // namespace lucent::texture_space
