// param_json.h: validates one JSON object of a scene file against its parameter declarations.
#pragma once
#include <initializer_list>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "lucent/params.h"

namespace lucent {

// Where a JSON value lives, for messages: "scene.json: /objects/0/material".
struct JsonLocation {
  std::string file;
  std::string pointer;  // JSON pointer, "" for the root
  JsonLocation child(std::string_view key) const { return {file, pointer + "/" + std::string(key)}; }
  JsonLocation child(std::size_t index) const { return child(std::to_string(index)); }
  std::string str() const { return file + ": " + (pointer.empty() ? "/" : pointer); }
};

// Checks `object` is a JSON object whose keys are all declared (or listed in `also_allowed`), each value
// of the declared type and within range, and returns every declared value with defaults filled in.
// Throws lucent::Error("<file>: <pointer>: <problem>").
ParamValues read_params(const nlohmann::json& object, const ParamSection& section, const JsonLocation& where,
                        std::initializer_list<std::string_view> also_allowed = {});

// Throws lucent::Error("<file>: <pointer>: <problem>"): the one error format of every JSON input.
[[noreturn]] void fail(const JsonLocation& where, const std::string& problem);

// Throws unless `value` is a JSON object.
void require_object(const nlohmann::json& value, const JsonLocation& where);

}  // namespace lucent
