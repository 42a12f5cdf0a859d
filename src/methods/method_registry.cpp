// method_registry.cpp: the rendering methods lucent knows, by name.
#include "methods/method.h"
#include "methods/per_pixel/per_pixel.h"
#include "methods/radiosity_maps/radiosity_maps.h"
#include "methods/voxel_paths/voxel_paths.h"

namespace lucent::methods {

std::span<const MethodInfo> method_registry() {
  static const MethodInfo methods[] = {
      {"radiosity-maps",
       "directional subsurface scattering cached in scattered-radiosity maps (Dal Corso et al. 2015)",
       radiosity_maps_params(), create_radiosity_maps},
      {"per-pixel",
       "caching-free baseline: the same light-space sampling per screen pixel every frame (Dal Corso et al. Fig. 11)",
       per_pixel_params(), create_per_pixel},
      {"voxel-paths",
       "shortest optical paths through a solid voxelization (Dijkstra-style relaxation on the GPU; first version)",
       voxel_paths_params(), create_voxel_paths},
  };
  return methods;
}

const MethodInfo* find_method(std::string_view name) {
  for (const MethodInfo& info : method_registry())
    if (info.name == name) return &info;
  return nullptr;
}

}  // namespace lucent::methods
