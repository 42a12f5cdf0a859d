// method_factory.cpp: creates a registered method's GPU side (GL library).
#include <fmt/format.h>

#include "lucent/error.h"
#include "methods/method.h"

namespace lucent::methods {

#define LUCENT_METHOD(id)                      \
  extern const MethodInfo id##_info;           \
  std::unique_ptr<Method> create_##id(const MethodSetup& setup);
#include "methods/method_list.h"
#undef LUCENT_METHOD

std::unique_ptr<Method> create_method(const MethodSetup& setup) {
  struct Entry {
    const MethodInfo* info;
    std::unique_ptr<Method> (*create)(const MethodSetup&);
  };
  static const Entry entries[] = {
#define LUCENT_METHOD(id) {&id##_info, create_##id},
#include "methods/method_list.h"
#undef LUCENT_METHOD
  };
  for (const Entry& entry : entries)
    if (entry.info->name == setup.scene.method) return entry.create(setup);
  throw Error(fmt::format("{}: unknown method '{}'", setup.scene.source, setup.scene.method));
}

}  // namespace lucent::methods
