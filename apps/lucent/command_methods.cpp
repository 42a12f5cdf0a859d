// command_methods.cpp: `lucent methods [--json]`: every registered method with its summary, parameters (type,
// default, unit, range, live or rebuild), passes and statistics, from the methods' own declarations.
#include <fmt/format.h>

#include "commands.h"
#include "lucent/params.h"
#include "methods/method_catalog.h"
#include "methods/method_info.h"

namespace lucent::cli {
namespace {

void run(bool as_json) {
  if (as_json) {
    fmt::print("{}\n", methods::method_catalog_json().dump(1));
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
  auto as_json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("methods", "list the rendering methods: parameters, passes and statistics");
  cmd->add_flag("--json", *as_json, "print them as JSON");
  cmd->callback([as_json] { run(*as_json); });
}

}  // namespace lucent::cli
