// params.h: parameters declared once (name, type, default, unit, range, doc). The declarations drive the
// scene parser's validation, the CLI's --help, --set overrides and the docs.
#pragma once
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

enum class ParamType { Int, Float, Bool, Enum, String, Vec2, Vec3, Vec3List };

// What a change of the parameter costs a running renderer: Live values are read every frame (a new value
// shows in the next frame, accumulation restarts where the result depends on it); Rebuild values size buffers
// or select shader code, so a change recreates the method (and may recompile its shaders).
enum class ParamUpdate { Rebuild, Live };

struct ParamDecl {
  std::string_view name;           // JSON key
  ParamType type;
  std::string_view default_json;   // default as JSON text ("" = required or no default)
  std::string_view unit;           // "" when unitless
  double min = -1e30;              // inclusive range for Int/Float and each Vec/Vec3List component
  double max = 1e30;
  std::string_view choices;        // Enum: "a|b|c"
  std::string_view doc;
  ParamUpdate update = ParamUpdate::Rebuild;

  constexpr ParamDecl(std::string_view name_, ParamType type_, std::string_view default_json_ = "",
                      std::string_view unit_ = "", double min_ = -1e30, double max_ = 1e30,
                      std::string_view choices_ = "", std::string_view doc_ = "",
                      ParamUpdate update_ = ParamUpdate::Rebuild)
      : name(name_), type(type_), default_json(default_json_), unit(unit_), min(min_), max(max_),
        choices(choices_), doc(doc_), update(update_) {}
};
inline constexpr ParamUpdate kLive = ParamUpdate::Live;

// A named group of declarations (one JSON object of the scene file).
struct ParamSection {
  std::string_view name;  // e.g. "method.radiosity-maps"
  std::span<const ParamDecl> params;
};

using ParamValue = std::variant<double, bool, std::string, glm::vec3, std::vector<glm::vec3>>;

// Values of one section after parsing; every declared parameter is present (defaults filled in).
class ParamValues {
 public:
  void set(std::string_view name, ParamValue value) { values_[std::string(name)] = std::move(value); }
  double number(std::string_view name) const;
  int integer(std::string_view name) const { return static_cast<int>(number(name)); }
  bool boolean(std::string_view name) const;
  const std::string& text(std::string_view name) const;
  glm::vec3 vec3(std::string_view name) const;
  const std::vector<glm::vec3>& vec3_list(std::string_view name) const;
  bool has(std::string_view name) const { return values_.count(std::string(name)) != 0; }
  const std::map<std::string, ParamValue>& all() const { return values_; }

 private:
  const ParamValue& get(std::string_view name) const;
  std::map<std::string, ParamValue> values_;
};

std::string_view to_string(ParamType type);
std::string_view to_string(ParamUpdate update);  // "live" or "rebuild"
std::string to_string(const ParamValue& value);
// "name  type  default  [min, max] unit  doc" lines for --help and docs.
std::string describe(const ParamSection& section, int indent = 2);

}  // namespace lucent
