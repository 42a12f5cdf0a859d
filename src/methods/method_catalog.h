// method_catalog.h: every registered method as JSON (name, summary, parameters with type, default, unit, range and
// live/rebuild, passes, statistics), from the methods' own declarations: `lucent methods --json` prints it and
// lucent.methods() returns it.
#pragma once
#include <nlohmann/json.hpp>

#include "lucent/params.h"

namespace lucent::methods {

nlohmann::ordered_json param_decl_json(const ParamDecl& decl);
nlohmann::ordered_json method_catalog_json();

}  // namespace lucent::methods
