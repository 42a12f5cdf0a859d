// param_json.h: the one JSON reader of every JSON input (scene files, --set values, bench configurations, volume
// headers, reference metadata), with its limits, and the validation of one JSON object of a scene file against its
// parameter declarations.
#pragma once
#include <cstddef>
#include <initializer_list>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "lucent/params.h"

namespace lucent {

// The deepest nesting of arrays and objects (the root counts as 1) that JSON input may have. The parser is
// iterative, but copying, comparing and printing a value recurse once per level: 60,000 levels overflow the stack.
inline constexpr std::size_t kMaxJsonDepth = 128;

// The most characters of a value (or of a JSON pointer, or of a --set argument) that an error message shows.
inline constexpr std::size_t kExcerptChars = 60;

// A --set assignment and the JSON pointer of the value it set: errors at or under that pointer name the
// assignment instead of the scene file.
struct JsonOverride {
  std::string pointer;     // "/method/K"
  std::string assignment;  // "method.K=0"
};

// Where a JSON value lives, for messages: "scene.json: /objects/0/material".
struct JsonLocation {
  std::string file;
  std::string pointer;                                   // JSON pointer, "" for the root
  const std::vector<JsonOverride>* overrides = nullptr;  // the --set assignments applied to the file, in order
  JsonLocation child(std::string_view key) const { return {file, pointer + "/" + std::string(key), overrides}; }
  JsonLocation child(std::size_t index) const { return child(std::to_string(index)); }
  // "scene.json: /objects/0", or "--set 'objects.0.shape=box': /objects/0/shape" at or under the pointer of an
  // override (the last such); the pointer cut to kExcerptChars.
  std::string str() const;
};

// Parses JSON text (comments allowed) into a value. Throws lucent::Error naming `where.file`:
//   "<file>: malformed JSON: line L, column C: <problem>" (also for numbers beyond double),
//   "<file>: <pointer>: duplicate key (each key may appear once in an object)",
//   "<file>: <pointer>: nested deeper than 128 levels" (kMaxJsonDepth).
// `where.pointer` is where the value will be placed (a --set value): its levels count toward kMaxJsonDepth and
// it prefixes the pointers of messages. The column (in bytes) is that of the last character read, as nlohmann
// reports it: the end of the offending token.
nlohmann::json parse_json(std::string_view text, const JsonLocation& where);
nlohmann::json parse_json(std::istream& in, const std::string& source);

// As parse_json, but text with a syntax error gives a discarded value (is_discarded()) instead of an error, for
// inputs that may be something else (a --set value is then a bare string). The limits still throw.
nlohmann::json try_parse_json(std::string_view text, const JsonLocation& where);
nlohmann::json try_parse_json(std::istream& in, const std::string& source);

// The first kExcerptChars characters of a value as compact JSON, "..." where cut: error messages never echo a
// whole value. Invalid UTF-8 in strings is replaced, never thrown.
std::string excerpt(const nlohmann::json& value);
// The same for text (a key, a file name, a --set argument); control characters become spaces.
std::string text_excerpt(std::string_view text);

// Checks `object` is a JSON object whose keys are all declared (or listed in `also_allowed`), each value
// of the declared type and within range, and returns every declared value with defaults filled in.
// Throws lucent::Error("<file>: <pointer>: <problem>").
ParamValues read_params(const nlohmann::json& object, const ParamSection& section, const JsonLocation& where,
                        std::initializer_list<std::string_view> also_allowed = {});

// Throws lucent::Error("<file>: <pointer>: <problem>"): the one error format of every JSON input.
[[noreturn]] void fail(const JsonLocation& where, const std::string& problem);

// Throws unless `value` is a JSON object.
void require_object(const nlohmann::json& value, const JsonLocation& where);

// The string at `key` of `object`, or `fallback` where absent; "<file>: <pointer>: expected a string, got 3" for
// another type (where json::value would throw a type_error).
std::string read_string(const nlohmann::json& object, std::string_view key, const std::string& fallback,
                        const JsonLocation& where);

}  // namespace lucent
