// method_catalog.cpp: the method registry as JSON.
#include "methods/method_catalog.h"

#include "methods/method_info.h"

namespace lucent::methods {
namespace {

nlohmann::ordered_json enum_choices(std::string_view rest) {
  nlohmann::ordered_json choices = nlohmann::ordered_json::array();
  while (!rest.empty()) {
    std::size_t bar = rest.find('|');
    choices.push_back(std::string(rest.substr(0, bar)));
    rest = bar == std::string_view::npos ? std::string_view{} : rest.substr(bar + 1);
  }
  return choices;
}

nlohmann::ordered_json method_json(const MethodInfo& m) {
  nlohmann::ordered_json j = {{"name", m.name}, {"summary", m.summary}, {"default", &m == &default_method()}};
  j["needs_texture_atlas"] = m.needs_texture_atlas;
  j["reads_material_maps"] = m.reads_material_maps;
  j["reference_tolerance"] = m.reference_tolerance;
  j["params"] = nlohmann::ordered_json::array();
  for (const ParamDecl& p : m.params) j["params"].push_back(param_decl_json(p));
  j["passes"] = nlohmann::ordered_json::array();
  for (const PassDecl& p : m.passes) j["passes"].push_back({{"name", p.name}, {"doc", p.doc}});
  j["stats"] = nlohmann::ordered_json::array();
  for (const StatDecl& s : m.stats) j["stats"].push_back({{"name", s.name}, {"unit", s.unit}, {"doc", s.doc}});
  return j;
}

}  // namespace

nlohmann::ordered_json param_decl_json(const ParamDecl& p) {
  nlohmann::ordered_json j = {{"name", p.name}, {"type", to_string(p.type)}};
  j["default"] = p.default_json.empty() ? nlohmann::ordered_json(nullptr)
                                        : nlohmann::ordered_json::parse(p.default_json, nullptr, false);
  j["unit"] = p.unit;
  if (p.type == ParamType::Enum) {
    j["choices"] = enum_choices(p.choices);
  } else if (p.type != ParamType::Bool && p.type != ParamType::String) {
    j["min"] = p.min, j["max"] = p.max;
  }
  j["update"] = to_string(p.update);
  j["doc"] = p.doc;
  return j;
}

nlohmann::ordered_json method_catalog_json() {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const MethodInfo* m : method_registry()) list.push_back(method_json(*m));
  return list;
}

}  // namespace lucent::methods
