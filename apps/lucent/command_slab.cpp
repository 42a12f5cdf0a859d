// command_slab.cpp: `lucent slab`: total diffuse reflectance and transmittance of a slab or half-space by Monte
// Carlo photon transport (the random walk and Fresnel code of the volumetric path tracer), with standard errors.
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "option_checks.h"
#include "lucent/error.h"
#include "bssrdf/multipole_table.h"
#include "transport/slab.h"

namespace lucent::cli {
namespace {

struct SlabOptions {
  reference::SlabConfig config;
  std::string thickness = "inf";
  std::string incidence = "normal";
  std::string model;  // "multipole": the model's totals of the same slab beside the transport's
  bool json = false;
};

nlohmann::json to_json(const reference::Estimate& e) { return {{"mean", e.mean}, {"standard_error", e.standard_error}}; }

void run(SlabOptions o) {
  if (o.thickness == "inf") {
    o.config.thickness = std::numeric_limits<double>::infinity();
  } else {
    try {
      std::size_t used = 0;
      o.config.thickness = std::stod(o.thickness, &used);
      if (used != o.thickness.size()) throw std::invalid_argument(o.thickness);
    } catch (const std::exception&) {
      throw Error(fmt::format("--thickness: '{}' is not a number or inf", o.thickness));
    }
    if (!std::isfinite(o.config.thickness))
      throw Error(fmt::format("--thickness: {} is not a finite number (write inf for a half-space)", o.thickness));
  }
  if (o.incidence != "normal" && o.incidence != "diffuse")
    throw Error(fmt::format("--incidence: '{}' is not one of normal, diffuse", o.incidence));
  o.config.incidence = o.incidence == "normal" ? reference::Incidence::Normal : reference::Incidence::Diffuse;
  if (!o.model.empty() && o.model != "multipole")
    throw Error(fmt::format("--model: '{}' is not multipole (the half-space models' totals: lucent materials)", o.model));
  const double a = o.config.albedo, g = o.config.g;
  const double alpha_prime = a * (1.0 - g) / (1.0 - a * g), reduced = 1.0 - a * g;  // reduced albedo, sigma_t'/sigma_t
  if (!o.model.empty() && !(alpha_prime > 0.0 && alpha_prime < 1.0))
    throw Error(fmt::format("--model multipole: the reduced albedo {} is outside (0, 1)", alpha_prime));
  reference::SlabResult r = reference::simulate_slab(o.config);
  // The model's totals per refracted power, against the transport's diffuse ones (unscattered light removed).
  glm::vec2 model(0.0f);
  const double refracted = 1.0 - r.specular_reflectance.mean;
  const reference::Estimate exact_R = r.diffuse_reflectance_per_refracted;
  const reference::Estimate exact_T{(r.transmittance.mean - r.unscattered_transmittance.mean) / refracted,
                                    r.transmittance.standard_error / refracted};
  if (!o.model.empty()) {
    const float d = std::isfinite(o.config.thickness) ? static_cast<float>(o.config.thickness * reduced) : 0.0f;
    model = multipole_table_totals(static_cast<float>(alpha_prime), static_cast<float>(o.config.eta), d);
  }
  if (o.json) {
    nlohmann::json out = {{"albedo", o.config.albedo}, {"g", o.config.g}, {"eta", o.config.eta},
                          {"thickness", o.thickness}, {"incidence", o.incidence}, {"photons", r.photons},
                          {"specular_reflectance", to_json(r.specular_reflectance)},
                          {"diffuse_reflectance", to_json(r.diffuse_reflectance)},
                          {"diffuse_reflectance_per_refracted", to_json(r.diffuse_reflectance_per_refracted)},
                          {"transmittance", to_json(r.transmittance)},
                          {"unscattered_transmittance", to_json(r.unscattered_transmittance)},
                          {"seconds", r.seconds}};
    if (!o.model.empty())
      out["model"] = {{"name", o.model},
                      {"diffuse_reflectance_per_refracted", model.x},
                      {"diffuse_transmittance_per_refracted", model.y},
                      {"transport_diffuse_transmittance_per_refracted", to_json(exact_T)}};
    fmt::print("{}\n", out.dump(2));
    return;
  }
  auto line = [](const char* name, const reference::Estimate& e) {
    fmt::print("{:<36} {:.6f} +- {:.6f}\n", name, e.mean, e.standard_error);
  };
  fmt::print("slab: albedo {} g {} eta {} thickness {} incidence {}, {} photons in {:.2f} s\n", o.config.albedo,
             o.config.g, o.config.eta, o.thickness, o.incidence, r.photons, r.seconds);
  line("specular reflectance", r.specular_reflectance);
  line("diffuse reflectance (per incident)", r.diffuse_reflectance);
  line("diffuse reflectance (per refracted)", r.diffuse_reflectance_per_refracted);
  line("transmittance (per incident)", r.transmittance);
  line("  of which unscattered", r.unscattered_transmittance);
  if (o.model.empty()) return;
  fmt::print("{:<36} {:<24} {:<9} {}\n", "per refracted power, diffuse:", "transport", o.model, "ratio");
  fmt::print("{:<36} {:.6f} +- {:.6f}   {:.6f}  {:.3f}\n", "  reflectance", exact_R.mean,
             exact_R.standard_error, model.x, model.x / exact_R.mean);
  fmt::print("{:<36} {:.6f} +- {:.6f}   {:.6f}  {:.3f}\n", "  transmittance", exact_T.mean,
             exact_T.standard_error, model.y, exact_T.mean > 0.0 ? model.y / exact_T.mean : 0.0);
}

}  // namespace

void add_slab_command(CLI::App& app) {
  auto o = std::make_shared<SlabOptions>();
  CLI::App* cmd = app.add_subcommand("slab", "reflectance and transmittance of a slab by Monte Carlo photon transport");
  cmd->add_option("--albedo", o->config.albedo, "single-scattering albedo sigma_s/sigma_t [0, 1]")->required();
  cmd->add_option("--g", o->config.g, "Henyey-Greenstein mean cosine (-1, 1)")->capture_default_str();
  cmd->add_option("--eta", o->config.eta, "relative refractive index n_medium/n_outside [1, 3]")->capture_default_str();
  cmd->add_option("--thickness", o->thickness, "optical thickness sigma_t d, or inf")->capture_default_str();
  cmd->add_option("--incidence", o->incidence, "normal (collimated) | diffuse (Lambertian)")->capture_default_str();
  cmd->add_option("--incidence-deg", o->config.incidence_deg, "angle of the collimated beam [degrees]")
      ->capture_default_str();
  cmd->add_option("--photons", o->config.photons, "photons to trace")
      ->check(whole_number_in(1, 1e12))
      ->capture_default_str();
  cmd->add_option("--seed", o->config.seed, "random seed")->check(whole_number_in(0, 1.8e19))->capture_default_str();
  cmd->add_option("--threads", o->config.threads, "threads (0 = all cores)")
      ->check(whole_number_in(0, 4096))
      ->capture_default_str();
  cmd->add_option("--model", o->model,
                  "also print the totals of this model for the same slab: multipole (the table the renderers read)");
  cmd->add_flag("--json", o->json, "print JSON");
  cmd->callback([o] { run(*o); });
}

}  // namespace lucent::cli
