// command_bssrdf.cpp: `lucent bssrdf`: S_d of a model at one configuration, per colour band, evaluated by the
// same header code the shaders compile. Units: mm and mm^-1; S_d in mm^-2. With --total: the model's flat
// half-space total diffuse reflectance per refracted power (materials/model_total_reflectance.h), the number to
// hold against `lucent slab`.
#include <array>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "option_checks.h"
#include "lucent/error.h"
#include "lucent/material.h"
#include "lucent/scene.h"
#include "materials/bssrdf_evaluation.h"
#include "materials/model_total_reflectance.h"
#include "params/argument_ranges.h"

namespace lucent::cli {
namespace {

struct BssrdfOptions {
  std::string model{to_string(kDefaultBssrdfModel)};
  std::string material;
  std::vector<float> sigma_a, sigma_s, sigma_s_prime, g;
  std::optional<float> eta;
  float thickness_mm = 0.0f;
  std::vector<float> xi{0, 0, 0}, ni{0, 0, 1}, wi{0, 0, 1}, xo{1, 0, 0}, no{0, 0, 1};
  bool json = false;
  bool total = false;
  double incidence_deg = 0.0;
};

glm::vec3 vec(const std::vector<float>& v, const char* name) {
  if (v.size() == 1) return glm::vec3(v[0]);
  if (v.size() != 3) throw Error(fmt::format("--{}: expected 3 comma-separated numbers", name));
  return {v[0], v[1], v[2]};
}

glm::vec3 unit_vec(const std::vector<float>& v, const char* name) {
  glm::vec3 u = vec(v, name);
  if (!(glm::length(u) > 0.0f)) throw Error(fmt::format("--{}: must be a non-zero vector", name));
  return glm::normalize(u);
}

Material material_of(const BssrdfOptions& o) {
  Material m;
  if (!o.material.empty()) {
    if (!o.sigma_a.empty() || !o.sigma_s.empty() || !o.sigma_s_prime.empty() || !o.g.empty())
      throw Error(fmt::format("--material {}: give either a preset or coefficients (--sigma-a, --sigma-s, "
                              "--sigma-s-prime, --g), not both", o.material));
    const MaterialPreset* preset = find_material_preset(o.material);
    if (!preset) throw Error(fmt::format("--material: unknown material '{}' (see: lucent materials)", o.material));
    m = material_from_preset(*preset);
  } else {
    if (o.sigma_a.empty() || (o.sigma_s.empty() == o.sigma_s_prime.empty()))
      throw Error("give --material NAME, or --sigma-a with one of --sigma-s (and --g) or --sigma-s-prime");
    m.sigma_a = vec(o.sigma_a, "sigma-a");
    m.sigma_s = o.sigma_s.empty() ? vec(o.sigma_s_prime, "sigma-s-prime") : vec(o.sigma_s, "sigma-s");
    m.g = o.g.empty() ? glm::vec3(0.0f) : vec(o.g, "g");
  }
  if (o.eta) m.eta = *o.eta;
  auto model = parse_bssrdf_model(o.model);
  if (!model)
    throw Error(fmt::format("--model: unknown model '{}'; known: directional, standard, photon-beam, better-dipole, tabulated, multipole", o.model));
  m.model = *model;
  m.thickness_mm = o.thickness_mm;
  validate_material(m, "bssrdf");
  return m;
}

void run_total(const BssrdfOptions& o, const Material& m) {
  const ModelTotalReflectance t = model_total_reflectance(m, o.incidence_deg);
  if (o.json) {
    nlohmann::json out = {{"model", to_string(m.model)},
                          {"material", m.name},
                          {"eta", m.eta},
                          {"incidence_deg", o.incidence_deg},
                          {"total", {t.total.x, t.total.y, t.total.z}},
                          {"radiosity", {t.radiosity.x, t.radiosity.y, t.radiosity.z}},
                          {"exit_transmittance", t.exit_transmittance}};
    fmt::print("{}\n", out.dump(2));
  } else {
    fmt::print("model {}  material {}  eta {}  incidence {} degrees\n", to_string(m.model), m.name, m.eta, o.incidence_deg);
    fmt::print("total diffuse reflectance per refracted power  R {:.5f}  G {:.5f}  B {:.5f}\n", t.total.x, t.total.y, t.total.z);
    fmt::print("  scattered radiosity (pi x integral of S_d)   R {:.5f}  G {:.5f}  B {:.5f}\n", t.radiosity.x, t.radiosity.y, t.radiosity.z);
    fmt::print("  exit transmittance (integral of T21 cos / pi) {:.5f}\n", t.exit_transmittance);
  }
}

void run(const BssrdfOptions& o) {
  Material m = material_of(o);
  if (o.total) return run_total(o, m);
  glm::vec3 x_i = vec(o.xi, "xi"), x_o = vec(o.xo, "xo");
  glm::vec3 n_i = unit_vec(o.ni, "ni"), w_i = unit_vec(o.wi, "wi"), n_o = unit_vec(o.no, "no");
  const BssrdfEvaluation e = evaluate_bssrdf(m, x_i, w_i, n_i, x_o, n_o);
  const std::array<float, 3> S = {e.S_d.x, e.S_d.y, e.S_d.z};
  const float T12 = e.T12;
  if (o.json) {
    nlohmann::json out = {{"model", to_string(m.model)}, {"material", m.name}, {"eta", m.eta},
                          {"S_d", S},                    {"T12", T12},         {"units", "mm^-2"}};
    fmt::print("{}\n", out.dump(2));
  } else {
    fmt::print("model {}  material {}  eta {}\n", to_string(m.model), m.name, m.eta);
    fmt::print("S_d [mm^-2]  R {:.6e}  G {:.6e}  B {:.6e}\n", S[0], S[1], S[2]);
    fmt::print("T12(w_i)     {:.6f}\n", T12);
  }
}

}  // namespace

// Help text of a material parameter, from the declarations the scene parser uses.
std::string doc(std::string_view name) {
  for (const ParamSection& section : scene_param_sections())
    if (section.name == "objects[].material")
      for (const ParamDecl& p : section.params)
        if (p.name == name) return fmt::format("{}{}", p.doc, p.unit.empty() ? "" : fmt::format(" [{}]", p.unit));
  return "";
}

void add_bssrdf_command(CLI::App& app) {
  auto options = std::make_shared<BssrdfOptions>();
  CLI::App* cmd = app.add_subcommand("bssrdf", "evaluate S_d of a diffusion model at one point (mm, mm^-1)");
  cmd->add_option("--model", options->model, doc("model") + ": directional | standard | photon-beam | better-dipole | tabulated | multipole")
      ->capture_default_str();
  cmd->add_option("--material", options->material, doc("preset"));
  cmd->add_option("--sigma-a", options->sigma_a, doc("sigma_a") + ", R,G,B")->delimiter(',')->check(number_in(argument_ranges::kCoefficient));
  cmd->add_option("--sigma-s", options->sigma_s, doc("sigma_s") + ", R,G,B")->delimiter(',')->check(number_in(argument_ranges::kCoefficient));
  cmd->add_option("--sigma-s-prime", options->sigma_s_prime, doc("sigma_s_prime") + ", R,G,B")->delimiter(',')->check(number_in(argument_ranges::kCoefficient));
  cmd->add_option("--g", options->g, doc("g"))->delimiter(',')->check(number_in(argument_ranges::kAnisotropy));
  cmd->add_option("--eta", options->eta, doc("eta"))->check(number_in(argument_ranges::kEta));
  cmd->add_option("--thickness-mm", options->thickness_mm, doc("thickness_mm"))->check(number_in(argument_ranges::kPointMm));
  cmd->add_option("--xi", options->xi, "entry point X,Y,Z [mm]")->delimiter(',')->check(number_in(argument_ranges::kPointMm))->capture_default_str();
  cmd->add_option("--ni", options->ni, "entry normal")->delimiter(',')->check(number_in(argument_ranges::kDirection))->capture_default_str();
  cmd->add_option("--wi", options->wi, "direction toward the light")->delimiter(',')->check(number_in(argument_ranges::kDirection))->capture_default_str();
  cmd->add_option("--xo", options->xo, "exit point X,Y,Z [mm]")->delimiter(',')->check(number_in(argument_ranges::kPointMm))->capture_default_str();
  cmd->add_option("--no", options->no, "exit normal")->delimiter(',')->check(number_in(argument_ranges::kDirection))->capture_default_str();
  cmd->add_flag("--total", options->total,
                "print the model's flat half-space total diffuse reflectance per refracted power instead of S_d");
  cmd->add_option("--incidence-deg", options->incidence_deg, "--total: angle of the incident light to the normal [degrees]")
      ->check(number_in(argument_ranges::kIncidenceDeg))
      ->needs("--total");
  cmd->add_flag("--json", options->json, "print JSON");
  cmd->callback([options] { run(*options); });
}

}  // namespace lucent::cli
