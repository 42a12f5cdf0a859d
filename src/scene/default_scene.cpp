// default_scene.cpp: the built-in scene `lucent render` uses without a scene file: scenes/default.json,
// embedded in the binary at build time (a potato torus and a marble sphere on a diffuse floor, side-lit).
#include <cstring>

#include "gpu/shader_sources.h"
#include "lucent/scene.h"

namespace lucent {

const char* default_scene_json() {
  for (std::size_t i = 0; i < gpu::kEmbeddedFileCount; ++i)
    if (std::strcmp(gpu::kEmbeddedFiles[i].path, "scenes/default.json") == 0) return gpu::kEmbeddedFiles[i].text;
  return "{}";
}

Scene default_scene(const std::vector<std::string>& overrides) {
  return parse_scene(default_scene_json(), "<built-in default scene>", ".", overrides);
}

}  // namespace lucent
