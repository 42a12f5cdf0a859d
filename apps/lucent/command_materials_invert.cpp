// command_materials_invert.cpp: `lucent materials invert`: coefficients from the surface albedo and the mean free
// path per band (materials/artist_parameters.h), or from Blender's Principled BSDF or OpenPBR subsurface inputs
// (--principled / --openpbr '<JSON>', materials/shader_material_json.h), printed as a scene material with the flat
// total they give.
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "lucent/error.h"
#include "lucent/material.h"
#include "materials/artist_parameters.h"
#include "materials/model_total_reflectance.h"
#include "materials/shader_material_json.h"
#include "materials/tabulated_bssrdf.h"
#include "option_checks.h"

namespace lucent::cli {
namespace {

struct InvertOptions {
  std::vector<float> albedo, mfp, g{0.0f};
  float eta = 1.3f;
  std::string model{to_string(kDefaultBssrdfModel)};
  bool json = false;
  std::string principled, openpbr;  // a JSON object of the block's keys
  double scale_mm = 1.0;
};

glm::vec3 per_band(const std::vector<float>& v, const char* name) {
  if (v.size() == 1) return glm::vec3(v[0]);
  if (v.size() != 3) throw Error(fmt::format("--{}: expected 1 or 3 comma-separated numbers", name));
  return {v[0], v[1], v[2]};
}

nlohmann::json array(glm::dvec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); }

// A float as the shortest decimal that reads back as the same float ("1.3", not 1.2999999523162842).
double shortest(float x) { return std::stod(fmt::format("{}", x)); }

// The scene-file material: coefficients in double from alpha and mfp (they round to the inverted floats).
nlohmann::json material_json(const ArtistParameters& a, const ArtistInversion& inv) {
  const glm::dvec3 sigma_t = 1.0 / glm::dvec3(a.mfp_mm);
  return {{"sigma_a", array((1.0 - inv.alpha) * sigma_t)}, {"sigma_s", array(inv.alpha * sigma_t)},
          {"g", {shortest(a.g.x), shortest(a.g.y), shortest(a.g.z)}}, {"eta", shortest(a.eta)},
          {"model", std::string(to_string(a.model))}};
}

// The tabulated model's own flat total (its tables by photon transport: seconds per band, then cached).
glm::dvec3 tabulated_total(const Material& m) {
  prepare_bssrdf_tables(m);
  return model_total_reflectance(m, 0.0).total;
}

void print_text(const ArtistParameters& a, const ArtistInversion& inv, const glm::dvec3* tabulated) {
  const Material& m = inv.material;
  fmt::print("model {}  eta {}  mean free path 1 / sigma_t (unreduced)\n", to_string(a.model), a.eta);
  fmt::print("{:<5} {:>8} {:>10} {:>7} {:>10} {:>14} {:>14} {:>11}\n", "band", "albedo", "mfp [mm]", "g", "alpha",
             "sigma_a [mm^-1]", "sigma_s [mm^-1]", "flat total");
  for (int b = 0; b < 3; ++b)
    fmt::print("{:<5} {:>8.4f} {:>10.4g} {:>7.3f} {:>10.6f} {:>15.6g} {:>15.6g} {:>11.5f}\n", "RGB"[b], a.albedo[b],
               a.mfp_mm[b], a.g[b], inv.alpha[b], m.sigma_a[b], m.sigma_s[b], inv.total[b]);
  // sqrt(3 sigma_a sigma_t') in double: the product underflows float for mean free paths past about 1e15 mm.
  const glm::dvec3 sigma_t_prime = glm::dvec3(m.sigma_a) + glm::dvec3(m.sigma_s) * (1.0 - glm::dvec3(m.g));
  const glm::dvec3 length = 1.0 / (glm::sqrt(3.0 * glm::dvec3(m.sigma_a)) * glm::sqrt(sigma_t_prime));
  fmt::print("diffusion length 1 / sigma_tr [mm]  R {:.4g}  G {:.4g}  B {:.4g}: an object much thicker than this shows "
             "the albedo; a thinner one transmits the band and shows less of it\n",
             length.x, length.y, length.z);
  if (inv.curve_model != a.model)
    fmt::print("flat total: the {} model's curve, which inverts the {} model\n", to_string(inv.curve_model),
               to_string(a.model));
  if (tabulated)
    fmt::print("the tabulated model's own flat total (photon transport)  R {:.5f}  G {:.5f}  B {:.5f}\n", tabulated->x,
               tabulated->y, tabulated->z);
}

// A scene-file material of coefficients (what a principled block becomes).
nlohmann::json coefficients_json(const Material& m) {
  return {{"sigma_a", array(glm::dvec3(m.sigma_a))}, {"sigma_s", array(glm::dvec3(m.sigma_s))},
          {"g", array(glm::dvec3(m.g))}, {"eta", shortest(m.eta)}, {"model", std::string(to_string(m.model))}};
}

// --principled / --openpbr: the block read as a scene file reads it, printed as coefficients and flat totals.
void run_shader_block(const InvertOptions& o) {
  const char* key = o.principled.empty() ? "openpbr" : "principled";
  const std::string& text = o.principled.empty() ? o.openpbr : o.principled;
  const JsonLocation where{fmt::format("--{}", key), ""};
  nlohmann::json material = {{key, parse_json(text, where)}, {"model", o.model}};
  if (!parse_bssrdf_model(o.model))
    throw Error(fmt::format("--model: unknown model '{}'; known: directional, standard, photon-beam, better-dipole, "
                            "tabulated, multipole", o.model));
  Material m = read_shader_material(material, {fmt::format("materials invert --{}", key), ""}, o.scale_mm);
  Material curve = m;
  curve.model = inversion_curve_model(m.model);
  const glm::dvec3 total = model_total_reflectance(curve, 0.0).total;
  if (o.json) {
    const nlohmann::json out = {{"material", coefficients_json(m)},
                                {"flat_total", array(total)},
                                {"flat_total_model", std::string(to_string(curve.model))}};
    return fmt::print("{}\n", out.dump(2));
  }
  fmt::print("{} block, scale_mm {}  ->  model {}  eta {}  g {}\n", key, o.scale_mm, to_string(m.model), m.eta, m.g.x);
  fmt::print("{:<5} {:>15} {:>15} {:>10} {:>11}\n", "band", "sigma_a [mm^-1]", "sigma_s [mm^-1]", "mfp [mm]",
             "flat total");
  for (int b = 0; b < 3; ++b)
    fmt::print("{:<5} {:>15.6g} {:>15.6g} {:>10.4g} {:>11.5f}\n", "RGB"[b], m.sigma_a[b], m.sigma_s[b],
               1.0 / (m.sigma_a[b] + m.sigma_s[b]), total[b]);
}

void run(const InvertOptions& o) {
  if (!o.principled.empty() || !o.openpbr.empty()) return run_shader_block(o);
  if (o.albedo.empty() || o.mfp.empty())
    throw Error("materials invert: give --albedo and --mfp, or --principled or --openpbr");
  ArtistParameters a;
  a.albedo = per_band(o.albedo, "albedo");
  a.mfp_mm = per_band(o.mfp, "mfp");
  a.g = per_band(o.g, "g");
  a.eta = o.eta;
  auto model = parse_bssrdf_model(o.model);
  if (!model)
    throw Error(fmt::format("--model: unknown model '{}'; known: directional, standard, photon-beam, better-dipole, "
                            "tabulated, multipole", o.model));
  a.model = *model;
  const ArtistInversion inv = invert_artist_parameters(a, "materials invert");
  const glm::dvec3 tabulated = a.model == BssrdfModel::Tabulated ? tabulated_total(inv.material) : glm::dvec3(0.0);
  if (!o.json) return print_text(a, inv, a.model == BssrdfModel::Tabulated ? &tabulated : nullptr);
  nlohmann::json out = {{"material", material_json(a, inv)},
                        {"alpha", array(inv.alpha)},
                        {"flat_total", array(inv.total)},
                        {"flat_total_model", std::string(to_string(inv.curve_model))}};
  if (a.model == BssrdfModel::Tabulated) out["tabulated_flat_total"] = array(tabulated);
  fmt::print("{}\n", out.dump(2));
}

}  // namespace

void add_materials_invert_command(CLI::App& materials) {
  auto o = std::make_shared<InvertOptions>();
  CLI::App* cmd = materials.add_subcommand(
      "invert", "coefficients from the surface albedo (the model's flat total reflectance) and the mean free path");
  const auto any = number_in(-1e30, 1e30);
  cmd->add_option("--albedo", o->albedo, "surface albedo per band, R,G,B (or one number), in (0, 1)")
      ->delimiter(',')->check(any);
  cmd->add_option("--mfp", o->mfp, "mean free path 1 / sigma_t per band (unreduced), R,G,B (or one number) [mm]")
      ->delimiter(',')->check(any);
  cmd->add_option("--g", o->g, "Henyey-Greenstein g, one number or R,G,B")->delimiter(',')->check(any)->capture_default_str();
  cmd->add_option("--eta", o->eta, "relative refractive index n_material / n_outside")->check(any)->capture_default_str();
  cmd->add_option("--model", o->model, "directional | standard | photon-beam | better-dipole | tabulated | multipole")
      ->capture_default_str();
  CLI::Option* principled = cmd->add_option(
      "--principled", o->principled,
      "Blender 3.4 Principled BSDF subsurface inputs as JSON, e.g. '{\"subsurface\": 1, \"subsurface_radius\": "
      "[1, 0.2, 0.1], \"subsurface_color\": [0.8, 0.4, 0.3]}' (docs/materials.md)");
  CLI::Option* openpbr = cmd->add_option(
      "--openpbr", o->openpbr,
      "OpenPBR subsurface inputs as JSON, e.g. '{\"subsurface_color\": [0.8, 0.4, 0.3], \"subsurface_radius\": 1}'");
  principled->excludes(openpbr);
  for (const char* name : {"--albedo", "--mfp", "--g", "--eta"}) {
    principled->excludes(name);
    openpbr->excludes(name);
  }
  cmd->add_option("--scale-mm", o->scale_mm, "--principled, --openpbr: millimetres per unit of their radii")
      ->check(number_in(1e-9, 1e9))->capture_default_str();
  cmd->add_flag("--json", o->json, "print JSON: {\"material\": <a scene-file material>, \"flat_total\": ...}");
  add_no_cache_flag(cmd);
  cmd->callback([o] { run(*o); });
}

}  // namespace lucent::cli
