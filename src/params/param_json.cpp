// param_json.cpp: the JSON reader (a SAX handler that builds the value and enforces the depth limit and unique
// keys) and JSON validation against parameter declarations (unknown keys, types, ranges, NaN).
#include "params/param_json.h"

#include <algorithm>
#include <cmath>
#include <istream>
#include <iterator>
#include <utility>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent {

void fail(const JsonLocation& where, const std::string& problem) {
  throw Error(fmt::format("{}: {}", where.str(), problem));
}

std::string JsonLocation::str() const {
  const std::string at = pointer.empty() ? "/" : text_excerpt(pointer);
  if (overrides) {
    for (auto o = overrides->rbegin(); o != overrides->rend(); ++o) {  // the last override of a value is in effect
      if (pointer == o->pointer || pointer.starts_with(o->pointer + "/"))
        return fmt::format("--set '{}': {}", text_excerpt(o->assignment), at);
    }
  }
  return file + ": " + at;
}

std::string text_excerpt(std::string_view text) {
  std::string out(text.substr(0, kExcerptChars));
  if (text.size() > kExcerptChars) {
    std::size_t cut = kExcerptChars - 3;
    while (cut > 0 && (static_cast<unsigned char>(out[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 sequence
    out.resize(cut);
    out += "...";
  }
  std::replace_if(out.begin(), out.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; }, ' ');
  return out;
}

std::string excerpt(const nlohmann::json& value) {
  return text_excerpt(value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

namespace {

using nlohmann::json;

// Line and column (1-based, in bytes) of the character before `position`: nlohmann reports the number of
// characters read, the offending one included.
std::string line_column(std::string_view text, std::size_t position) {
  const std::size_t at = std::min(position == 0 ? 0 : position - 1, text.size());
  const std::string_view before = text.substr(0, at);
  const std::size_t line = 1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t line_start = before.rfind('\n') == std::string_view::npos ? 0 : before.rfind('\n') + 1;
  return fmt::format("line {}, column {}", line, at - line_start + 1);
}

// nlohmann's message without its "[json.exception...] parse error at line L, column C: " prefix, and with the
// token it quotes (which may be a whole long string) cut.
std::string parse_problem(const json::exception& e) {
  std::string what = e.what();
  if (auto bracket = what.find("] "); bracket != std::string::npos) what.erase(0, bracket + 2);
  if (what.starts_with("parse error"))
    if (auto colon = what.find(": "); colon != std::string::npos) what.erase(0, colon + 2);
  if (auto quote = what.find('\''); quote != std::string::npos)
    what = what.substr(0, quote) + text_excerpt(std::string_view(what).substr(quote));
  return what;
}

// Builds the value like nlohmann's own DOM parser, and stops at the first key an object already has or the first
// array or object nested deeper than kMaxJsonDepth, before anything recursive runs on the value.
class CheckedDomBuilder {
 public:
  CheckedDomBuilder(std::string_view text, const JsonLocation& where)
      : text_(text),
        where_(where),
        enclosing_(static_cast<std::size_t>(std::count(where.pointer.begin(), where.pointer.end(), '/'))) {}

  bool null() { return scalar(nullptr); }
  bool boolean(bool b) { return scalar(b); }
  bool number_integer(json::number_integer_t x) { return scalar(x); }
  bool number_unsigned(json::number_unsigned_t x) { return scalar(x); }
  bool number_float(json::number_float_t x, const json::string_t&) { return scalar(x); }
  bool string(json::string_t& s) { return scalar(std::move(s)); }
  bool binary(json::binary_t& b) { return scalar(std::move(b)); }
  bool start_object(std::size_t) { return open(json::value_t::object); }
  bool start_array(std::size_t) { return open(json::value_t::array); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(json::string_t& k) {
    if (open_.back()->contains(k))
      return stop(pointers_.back() + "/" + k, "duplicate key (each key may appear once in an object)");
    key_ = std::move(k);
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const json::exception& e) {
    syntax_error_ = dynamic_cast<const json::parse_error*>(&e) != nullptr;
    error_ = fmt::format("{}: malformed JSON: {}: {}", where_.file, line_column(text_, position), parse_problem(e));
    return false;
  }

  // The value, or a discarded one after a syntax error when `syntax_errors_throw` is false.
  json result(bool parsed, bool syntax_errors_throw) {
    if (parsed) return std::move(root_);
    if (syntax_error_ && !syntax_errors_throw) return json(json::value_t::discarded);
    throw Error(error_);
  }

 private:
  // Places a value in the open array or object (or as the root); returns it.
  template <class Value>
  json* add(Value&& value) {
    if (open_.empty()) {
      root_ = json(std::forward<Value>(value));
      return &root_;
    }
    json& parent = *open_.back();
    if (parent.is_array()) {
      parent.push_back(json(std::forward<Value>(value)));
      return &parent.back();
    }
    json& slot = parent[key_];
    slot = json(std::forward<Value>(value));
    return &slot;
  }

  template <class Value>
  bool scalar(Value&& value) {
    add(std::forward<Value>(value));
    return true;
  }

  // The JSON pointer of the next value placed.
  std::string next_pointer() const {
    if (open_.empty()) return where_.pointer;
    return pointers_.back() + "/" + (open_.back()->is_array() ? std::to_string(open_.back()->size()) : key_);
  }

  bool open(json::value_t type) {
    std::string pointer = next_pointer();
    if (enclosing_ + open_.size() + 1 > kMaxJsonDepth)
      return stop(pointer, fmt::format("nested deeper than {} levels", kMaxJsonDepth));
    open_.push_back(add(type));
    pointers_.push_back(std::move(pointer));
    return true;
  }

  bool close() {
    open_.pop_back();
    pointers_.pop_back();
    return true;
  }

  bool stop(const std::string& pointer, const std::string& problem) {
    error_ = fmt::format("{}: {}: {}", where_.file, text_excerpt(pointer), problem);
    return false;
  }

  std::string_view text_;
  const JsonLocation& where_;
  std::size_t enclosing_;  // levels above the value (those of where_.pointer)
  json root_;
  std::vector<json*> open_;            // the arrays and objects being filled, outermost first
  std::vector<std::string> pointers_;  // their JSON pointers
  std::string key_;                    // the key of the next value in the innermost object
  bool syntax_error_ = false;
  std::string error_;
};

json read_json(std::string_view text, const JsonLocation& where, bool syntax_errors_throw) {
  CheckedDomBuilder builder(text, where);
  bool parsed = json::sax_parse(text, &builder, json::input_format_t::json, /*strict=*/true, /*ignore_comments=*/true);
  return builder.result(parsed, syntax_errors_throw);
}

std::string read_stream(std::istream& in) {
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

json parse_json(std::string_view text, const JsonLocation& where) { return read_json(text, where, true); }
json parse_json(std::istream& in, const std::string& source) { return parse_json(read_stream(in), {source, ""}); }
json try_parse_json(std::string_view text, const JsonLocation& where) { return read_json(text, where, false); }
json try_parse_json(std::istream& in, const std::string& source) {
  return try_parse_json(read_stream(in), {source, ""});
}

namespace {

// The bounds the value is checked against, also the default +-1e30 (a float's range with room to spare).
std::string allowed_range(const ParamDecl& p) {
  return fmt::format("allowed range [{:g}, {:g}]{}", p.min, p.max, p.unit.empty() ? "" : " " + std::string(p.unit));
}

double read_number(const nlohmann::json& v, const ParamDecl& p, const JsonLocation& where) {
  if (v.is_string() && (v == "nan" || v == "NaN")) fail(where, "NaN is not allowed; " + allowed_range(p));
  if (!v.is_number()) fail(where, fmt::format("expected a number, got {}", excerpt(v)));
  double x = v.get<double>();
  if (!std::isfinite(x)) fail(where, fmt::format("{} is not finite; {}", excerpt(v), allowed_range(p)));
  if (x < p.min || x > p.max) fail(where, fmt::format("{:g} is out of range; {}", x, allowed_range(p)));
  if (p.type == ParamType::Int && x != std::floor(x)) fail(where, fmt::format("{:g} is not an integer", x));
  return x;
}

glm::vec3 read_vector(const nlohmann::json& v, const ParamDecl& p, const JsonLocation& where) {
  std::size_t n = p.type == ParamType::Vec2 ? 2 : 3;
  if (!v.is_array() || v.size() != n)
    fail(where, fmt::format("expected an array of {} numbers, got {}", n, excerpt(v)));
  glm::vec3 out(0.0f);
  for (std::size_t i = 0; i < n; ++i) out[static_cast<int>(i)] = static_cast<float>(read_number(v[i], p, where.child(i)));
  return out;
}

std::string read_enum(const nlohmann::json& v, const ParamDecl& p, const JsonLocation& where) {
  if (!v.is_string()) fail(where, fmt::format("expected one of {{{}}}, got {}", p.choices, excerpt(v)));
  std::string s = v.get<std::string>();
  std::string_view choices = p.choices;
  while (!choices.empty()) {
    auto bar = choices.find('|');
    if (choices.substr(0, bar) == s) return s;
    if (bar == std::string_view::npos) break;
    choices.remove_prefix(bar + 1);
  }
  fail(where, fmt::format("'{}' is not one of {{{}}}", text_excerpt(s), p.choices));
}

ParamValue read_value(const nlohmann::json& v, const ParamDecl& p, const JsonLocation& where) {
  switch (p.type) {
    case ParamType::Int:
    case ParamType::Float: return read_number(v, p, where);
    case ParamType::Bool:
      if (!v.is_boolean()) fail(where, fmt::format("expected true or false, got {}", excerpt(v)));
      return v.get<bool>();
    case ParamType::Enum: return read_enum(v, p, where);
    case ParamType::String:
      if (!v.is_string()) fail(where, fmt::format("expected a string, got {}", excerpt(v)));
      return v.get<std::string>();
    case ParamType::Vec2:
    case ParamType::Vec3: return read_vector(v, p, where);
    case ParamType::Vec3List: {
      if (!v.is_array()) fail(where, fmt::format("expected an array of [x, y, z] arrays, got {}", excerpt(v)));
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
  if (!value.is_object()) fail(where, fmt::format("expected a JSON object, got {}", excerpt(value)));
}

std::string read_string(const nlohmann::json& object, std::string_view key, const std::string& fallback,
                        const JsonLocation& where) {
  auto it = object.find(key);
  if (it == object.end()) return fallback;
  if (!it->is_string()) fail(where.child(key), fmt::format("expected a string, got {}", excerpt(*it)));
  return it->get<std::string>();
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
