// param_decl.cpp: ParamValues access and human-readable descriptions of parameter declarations.
#include <fmt/format.h>

#include "lucent/error.h"
#include "lucent/params.h"

namespace lucent {

const ParamValue& ParamValues::get(std::string_view name) const {
  auto it = values_.find(std::string(name));
  if (it == values_.end()) throw Error(fmt::format("parameter '{}' is not declared", name));
  return it->second;
}

double ParamValues::number(std::string_view name) const { return std::get<double>(get(name)); }
bool ParamValues::boolean(std::string_view name) const { return std::get<bool>(get(name)); }
const std::string& ParamValues::text(std::string_view name) const { return std::get<std::string>(get(name)); }
glm::vec3 ParamValues::vec3(std::string_view name) const { return std::get<glm::vec3>(get(name)); }
const std::vector<glm::vec3>& ParamValues::vec3_list(std::string_view name) const {
  return std::get<std::vector<glm::vec3>>(get(name));
}

std::string_view to_string(ParamType type) {
  switch (type) {
    case ParamType::Int: return "int";
    case ParamType::Float: return "float";
    case ParamType::Bool: return "bool";
    case ParamType::Enum: return "enum";
    case ParamType::String: return "string";
    case ParamType::Vec2: return "vec2";
    case ParamType::Vec3: return "vec3";
    case ParamType::Vec3List: return "vec3[]";
  }
  return "?";
}

std::string_view to_string(ParamUpdate update) { return update == ParamUpdate::Live ? "live" : "rebuild"; }

std::string to_string(const ParamValue& value) {
  if (auto* d = std::get_if<double>(&value)) return fmt::format("{:g}", *d);
  if (auto* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (auto* s = std::get_if<std::string>(&value)) return *s;
  if (auto* list = std::get_if<std::vector<glm::vec3>>(&value)) {
    std::string out;
    for (const glm::vec3& v : *list) out += fmt::format("{}[{:g}, {:g}, {:g}]", out.empty() ? "" : ", ", v.x, v.y, v.z);
    return "[" + out + "]";
  }
  auto v = std::get<glm::vec3>(value);
  return fmt::format("[{:g}, {:g}, {:g}]", v.x, v.y, v.z);
}

static std::string range_text(const ParamDecl& p) {
  if (p.type == ParamType::Enum) return fmt::format("{{{}}}", p.choices);
  if (p.type == ParamType::Bool || p.type == ParamType::String) return "";
  return fmt::format("[{:g}, {:g}]", p.min, p.max);  // the bounds checked, also the default +-1e30
}

std::string describe(const ParamSection& section, int indent) {
  std::string out;
  std::string pad(static_cast<std::size_t>(indent), ' ');
  for (const ParamDecl& p : section.params) {
    std::string def = p.default_json.empty() ? "(required)" : std::string(p.default_json);
    std::string range = range_text(p);
    if (!p.unit.empty()) range += (range.empty() ? "" : " ") + std::string(p.unit);
    out += fmt::format("{}{:<16} {:<6} {:<14} {:<24} {:<7} {}\n", pad, p.name, to_string(p.type), def, range,
                       to_string(p.update), p.doc);
  }
  return out;
}

}  // namespace lucent
