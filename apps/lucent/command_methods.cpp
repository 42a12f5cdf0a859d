// command_methods.cpp: `lucent methods [--json]`: every registered method with its summary, parameters (type,
// default, unit, range, live or rebuild), passes and statistics, from the methods' own declarations.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "lucent/params.h"
#include "methods/method_info.h"

namespace lucent::cli {
namespace {

nlohmann::ordered_json param_json(const ParamDecl& p) {
  nlohmann::ordered_json j = {{"name", p.name}, {"type", to_string(p.type)}};
  j["default"] = p.default_json.empty() ? nlohmann::ordered_json(nullptr)
                                        : nlohmann::ordered_json::parse(p.default_json, nullptr, false);
  j["unit"] = p.unit;
  if (p.type == ParamType::Enum) {
    nlohmann::ordered_json choices = nlohmann::ordered_json::array();
    std::string_view rest = p.choices;
    while (!rest.empty()) {
      std::size_t bar = rest.find('|');
      choices.push_back(std::string(rest.substr(0, bar)));
      rest = bar == std::string_view::npos ? std::string_view{} : rest.substr(bar + 1);
    }
    j["choices"] = choices;
  } else if (p.type != ParamType::Bool && p.type != ParamType::String) {
    j["min"] = p.min, j["max"] = p.max;
  }
  j["update"] = to_string(p.update);
  j["doc"] = p.doc;
  return j;
}

void run(bool json) {
  if (json) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const methods::MethodInfo* m : methods::method_registry()) {
      nlohmann::ordered_json j = {{"name", m->name}, {"summary", m->summary}, {"default", m == &methods::default_method()}};
      j["needs_texture_atlas"] = m->needs_texture_atlas;
      j["reference_tolerance"] = m->reference_tolerance;
      j["params"] = nlohmann::ordered_json::array();
      for (const ParamDecl& p : m->params) j["params"].push_back(param_json(p));
      j["passes"] = nlohmann::ordered_json::array();
      for (const methods::PassDecl& p : m->passes) j["passes"].push_back({{"name", p.name}, {"doc", p.doc}});
      j["stats"] = nlohmann::ordered_json::array();
      for (const methods::StatDecl& s : m->stats)
        j["stats"].push_back({{"name", s.name}, {"unit", s.unit}, {"doc", s.doc}});
      list.push_back(j);
    }
    fmt::print("{}\n", list.dump(1));
    return;
  }
  for (const methods::MethodInfo* m : methods::method_registry()) {
    fmt::print("{}{}\n  {}\n", m->name, m == &methods::default_method() ? " (default)" : "", m->summary);
    fmt::print("  parameters (method.<name>; live: read every frame, rebuild: recreates the method):\n{}",
               describe({m->name, m->params}, 4));
    fmt::print("  passes:\n");
    for (const methods::PassDecl& p : m->passes) fmt::print("    {:<18} {}\n", p.name, p.doc);
    fmt::print("  statistics:\n");
    for (const methods::StatDecl& s : m->stats)
      fmt::print("    {:<26} {:<4} {}\n", s.name, s.unit, s.doc);
    fmt::print("\n");
  }
}

}  // namespace

void add_methods_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("methods", "list the rendering methods: parameters, passes and statistics");
  cmd->add_flag("--json", *json, "print them as JSON");
  cmd->callback([json] { run(*json); });
}

}  // namespace lucent::cli
