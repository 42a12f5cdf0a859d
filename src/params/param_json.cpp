// param_json.cpp: JSON validation against parameter declarations (unknown keys, types, ranges, NaN).
#include "params/param_json.h"

#include <cmath>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent {

void fail(const JsonLocation& where, const std::string& problem) {
  throw Error(fmt::format("{}: {}", where.str(), problem));
}

namespace {

std::string allowed_range(const ParamDecl& p) {
  if (p.min <= -1e29 && p.max >= 1e29) return "any finite number";
  std::string lo = p.min <= -1e29 ? "-inf" : fmt::format("{:g}", p.min);
  std::string hi = p.max >= 1e29 ? "inf" : fmt::format("{:g}", p.max);
  std::string unit = p.unit.empty() ? "" : " " + std::string(p.unit);
  return fmt::format("allowed range [{}, {}]{}", lo, hi, unit);
}

double read_number(const nlohmann::json& v, const ParamDecl& p, const JsonLocation& where) {
  if (v.is_string() && (v == "nan" || v == "NaN")) fail(where, "NaN is not allowed; " + allowed_range(p));
  if (!v.is_number()) fail(where, fmt::format("expected a number, got {}", v.dump()));
  double x = v.get<double>();
  if (!std::isfinite(x)) fail(where, fmt::format("{} is not finite; {}", v.dump(), allowed_range(p)));
  if (x < p.min || x > p.max) fail(where, fmt::format("{:g} is out of range; {}", x, allowed_range(p)));
  if (p.type == ParamType::Int && x != std::floor(x)) fail(where, fmt::format("{:g} is not an integer", x));
  return x;
}

glm::vec3 read_vector(const nlohmann::json& v, const ParamDecl& p, const JsonLocation& where) {
  std::size_t n = p.type == ParamType::Vec2 ? 2 : 3;
  if (!v.is_array() || v.size() != n) fail(where, fmt::format("expected an array of {} numbers, got {}", n, v.dump()));
  glm::vec3 out(0.0f);
  for (std::size_t i = 0; i < n; ++i) out[static_cast<int>(i)] = static_cast<float>(read_number(v[i], p, where.child(i)));
  return out;
}

std::string read_enum(const nlohmann::json& v, const ParamDecl& p, const JsonLocation& where) {
  if (!v.is_string()) fail(where, fmt::format("expected one of {{{}}}, got {}", p.choices, v.dump()));
  std::string s = v.get<std::string>();
  std::string_view choices = p.choices;
  while (!choices.empty()) {
    auto bar = choices.find('|');
    if (choices.substr(0, bar) == s) return s;
    if (bar == std::string_view::npos) break;
    choices.remove_prefix(bar + 1);
  }
  fail(where, fmt::format("'{}' is not one of {{{}}}", s, p.choices));
}

ParamValue read_value(const nlohmann::json& v, const ParamDecl& p, const JsonLocation& where) {
  switch (p.type) {
    case ParamType::Int:
    case ParamType::Float: return read_number(v, p, where);
    case ParamType::Bool:
      if (!v.is_boolean()) fail(where, fmt::format("expected true or false, got {}", v.dump()));
      return v.get<bool>();
    case ParamType::Enum: return read_enum(v, p, where);
    case ParamType::String:
      if (!v.is_string()) fail(where, fmt::format("expected a string, got {}", v.dump()));
      return v.get<std::string>();
    case ParamType::Vec2:
    case ParamType::Vec3: return read_vector(v, p, where);
    case ParamType::Vec3List: {
      if (!v.is_array()) fail(where, fmt::format("expected an array of [x, y, z] arrays, got {}", v.dump()));
      std::vector<glm::vec3> list;
      ParamDecl element = p;
      element.type = ParamType::Vec3;
      for (std::size_t i = 0; i < v.size(); ++i) list.push_back(read_vector(v[i], element, where.child(i)));
      return list;
    }
  }
  fail(where, "unsupported parameter type");
}

std::string known_keys(const ParamSection& section, std::initializer_list<std::string_view> also_allowed) {
  std::string out;
  for (const ParamDecl& p : section.params) out += (out.empty() ? "" : ", ") + std::string(p.name);
  for (std::string_view k : also_allowed) out += (out.empty() ? "" : ", ") + std::string(k);
  return out;
}

}  // namespace

void require_object(const nlohmann::json& value, const JsonLocation& where) {
  if (!value.is_object()) fail(where, fmt::format("expected a JSON object, got {}", value.dump()));
}

ParamValues read_params(const nlohmann::json& object, const ParamSection& section, const JsonLocation& where,
                        std::initializer_list<std::string_view> also_allowed) {
  require_object(object, where);
  for (const auto& [key, value] : object.items()) {
    bool known = false;
    for (const ParamDecl& p : section.params) known = known || p.name == key;
    for (std::string_view k : also_allowed) known = known || k == key;
    if (!known) fail(where.child(key), fmt::format("unknown key; known keys: {}", known_keys(section, also_allowed)));
  }
  ParamValues values;
  for (const ParamDecl& p : section.params) {
    JsonLocation at = where.child(p.name);
    if (object.contains(p.name)) {
      values.set(p.name, read_value(object.at(std::string(p.name)), p, at));
    } else if (!p.default_json.empty()) {
      values.set(p.name, read_value(nlohmann::json::parse(p.default_json), p, at));
    }
  }
  return values;
}

}  // namespace lucent
