// command_materials.cpp: `lucent materials`: the measured presets with coefficients, units and source.
#include <fmt/format.h>

#include "commands.h"
#include "lucent/error.h"
#include "lucent/material.h"

namespace lucent::cli {

void add_materials_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("materials", "list the measured material presets (coefficients in mm^-1)");
  add_materials_invert_command(*cmd);
  cmd->callback([cmd] {
    if (cmd->got_subcommand("invert")) return;
    fmt::print("{:<26} {:<28} {:<28} {:<22} {:<5} {}\n", "name", "sigma_a [mm^-1]", "sigma_s [mm^-1]", "g", "eta",
               "source");
    for (const MaterialPreset& p : material_presets()) {
      auto v3 = [](glm::vec3 v) { return fmt::format("{:.4g} {:.4g} {:.4g}", v.x, v.y, v.z); };
      std::string usable;
      try {
        validate_material(material_from_preset(p), p.name);
      } catch (const Error&) {
        usable = " [not usable by the diffusion models: a zero coefficient]";
      }
      fmt::print("{:<26} {:<28} {:<28} {:<22} {:<5} {}{}{}\n", p.name, v3(p.sigma_a),
                 v3(p.sigma_s) + (p.reduced ? " (reduced)" : ""), v3(p.g), p.eta, p.source, usable,
                 p.note[0] ? std::string("; ") + p.note : "");
    }
  });
}

}  // namespace lucent::cli
