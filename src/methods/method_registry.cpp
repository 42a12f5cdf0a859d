// method_registry.cpp: the registered methods' descriptions, by name (no GL: part of the core library).
#include <stdexcept>

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

}  // namespace lucent::methods
