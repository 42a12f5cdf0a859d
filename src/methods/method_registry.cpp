// method_registry.cpp: the registered methods' descriptions, by name (no GL: part of the core library).
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "lucent/error.h"
#include "lucent/scene.h"
#include "methods/method_info.h"

namespace lucent::methods {

#define LUCENT_METHOD(id) extern const MethodInfo id##_info;
#include "methods/method_list.h"
#undef LUCENT_METHOD

std::span<const MethodInfo* const> method_registry() {
  static const MethodInfo* const methods[] = {
#define LUCENT_METHOD(id) &id##_info,
#include "methods/method_list.h"
#undef LUCENT_METHOD
  };
  return methods;
}

const MethodInfo* find_method(std::string_view name) {
  for (const MethodInfo* info : method_registry())
    if (info->name == name) return info;
  return nullptr;
}

const MethodInfo& default_method() { return *method_registry().front(); }

const MethodInfo* volpath_method() {
  for (const MethodInfo* info : method_registry())
    if (info->estimates_volpath) return info;
  return nullptr;
}

void refuse_material_maps(const Scene& scene, const MethodInfo& method) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const std::optional<Material>& material = scene.objects[i].material;
    if (!material || !material->maps) continue;
    std::string readers;
    for (const MethodInfo* info : method_registry())
      if (info->reads_material_maps) readers += (readers.empty() ? "" : ", ") + std::string(info->name);
    const char* key = material->maps->albedo_file.empty() ? "mfp_map" : "albedo_map";
    throw Error(fmt::format("{}: /objects/{}/material/{}: method '{}' does not read textured materials (methods that "
                            "do: {}; the references lucent reference --integrator volpath|bssrdf do)",
                            scene.source, i, key, method.name, readers.empty() ? "none" : readers));
  }
}

}  // namespace lucent::methods
