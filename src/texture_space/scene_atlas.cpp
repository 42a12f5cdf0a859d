// scene_atlas.cpp: see scene_atlas.h.
#include "texture_space/scene_atlas.h"

#include <fmt/format.h>

#include "lucent/error.h"
#include "texture_space/atlas_encoding.h"

namespace lucent::texture_space {
namespace {

std::vector<std::size_t> translucent_objects(const Scene& scene) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    if (!object.translucent()) continue;
    if (object.blob_resolution > 0)
      throw Error(fmt::format("{}: object '{}': a blob surface has no stable texture parameterisation (it is "
                              "re-extracted every frame); texture-space methods need a mesh",
                              scene.source, object.name));
    out.push_back(i);
  }
  if (out.empty()) throw Error(fmt::format("{}: no translucent object to lay out in a texture atlas", scene.source));
  return out;
}

}  // namespace

SceneAtlas build_scene_atlas(const Scene& scene, const AtlasOptions& options) {
  SceneAtlas out;
  out.object_index = translucent_objects(scene);
  if (out.object_index.size() == 1 && options.use_own_uvs) {
    const SceneObject& object = scene.objects[out.object_index.front()];
    if (!object.mesh.uvs.empty()) {
      std::optional<std::string> problem = uv_problem(object.mesh, options.size);
      if (!problem) {
        out.own_uvs = true;
        out.atlas.size = options.size;
        AtlasObject own;
        own.mesh = object.mesh;
        for (std::size_t v = 0; v < own.mesh.positions.size(); ++v) own.source_vertex.push_back(static_cast<std::uint32_t>(v));
        own.chart.assign(own.mesh.indices.size() / 3, 0);
        out.atlas.objects.push_back(std::move(own));
        out.atlas.metrics = uv_metrics(object.mesh, options.size);
        return out;
      }
      out.own_uv_problem = *problem;
    }
  }
  std::vector<AtlasInput> inputs;
  for (std::size_t i : out.object_index) inputs.push_back({&scene.objects[i].mesh, scene.objects[i].world_from_object});
  out.atlas = build_atlas(inputs, options);
  return out;
}

Scene with_atlas_meshes(const Scene& scene, const SceneAtlas& atlas) {
  Scene out = scene;
  for (std::size_t k = 0; k < atlas.object_index.size(); ++k) {
    const AtlasObject& object = atlas.atlas.objects[k];
    TriangleMesh& mesh = out.objects[atlas.object_index[k]].mesh;
    const std::vector<glm::vec2>& own = mesh.uvs;
    // A textured material keeps reading its maps through the mesh's own texture coordinates.
    std::vector<glm::vec2> material_uvs;
    if (!own.empty() && out.objects[atlas.object_index[k]].material && out.objects[atlas.object_index[k]].material->textured()) {
      material_uvs.reserve(object.source_vertex.size());
      for (std::uint32_t v : object.source_vertex) material_uvs.push_back(own[v]);
    }
    mesh = object.mesh;
    mesh.material_uvs = std::move(material_uvs);
  }
  return out;
}

cache::Key atlas_cache_key(const Scene& scene, const AtlasOptions& options) {
  cache::Key key("texture-atlas", kSceneAtlasEncodingVersion);
  key.integer(kAtlasBuilderVersion).integer(options.size).number(options.cone_deg).integer(options.border_texels);
  key.integer(options.use_own_uvs ? 1 : 0);
  for (std::size_t i : translucent_objects(scene)) {
    const SceneObject& object = scene.objects[i];
    key.integer(static_cast<std::int64_t>(i)).mesh(object.mesh);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) key.number(object.world_from_object[c][r]);
  }
  return key;
}

}  // namespace lucent::texture_space
