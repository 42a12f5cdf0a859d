// bssrdf.cpp: lucent.bssrdf and lucent.bssrdf_total: S_d of a diffusion model at one configuration and the
// model's flat half-space total reflectance, as `lucent bssrdf [--total] --json` print them. Units: mm, mm^-1,
// S_d in mm^-2.
#include <memory>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "arguments.h"
#include "bindings.h"
#include "long_call.h"
#include "lucent/error.h"
#include "lucent/material.h"
#include "materials/bssrdf_evaluation.h"
#include "materials/model_total_reflectance.h"
#include "params/argument_ranges.h"

namespace lucent::python {
namespace {

// A number or three numbers (R, G, B; X, Y, Z), each in the range of the CLI's option of that name.
glm::vec3 rgb(const py::handle& value, const NumberRange& range, const std::string& name) {
  const std::vector<double> v = numbers_argument(value, range, name);
  if (v.size() == 1) return glm::vec3(static_cast<float>(v[0]));
  if (v.size() != 3) throw Error(fmt::format("{}: expected a number or 3 numbers, got {}", name, v.size()));
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

glm::vec3 unit(const py::handle& value, const std::string& name) {
  glm::vec3 u = rgb(value, argument_ranges::kDirection, name);
  if (!(glm::length(u) > 0.0f)) throw Error(fmt::format("{}: must be a non-zero vector", name));
  return glm::normalize(u);
}

// A preset name, or a dict of coefficients: sigma_a with sigma_s (and g) or sigma_s_prime, and eta [mm^-1].
Material coefficients(const py::dict& d) {
  for (auto [key, value] : d) {
    const std::string k = py::str(key);
    if (k != "sigma_a" && k != "sigma_s" && k != "sigma_s_prime" && k != "g" && k != "eta" && k != "thickness_mm")
      throw Error(
          fmt::format("material: unknown key '{}'; known: sigma_a, sigma_s, sigma_s_prime, g, eta, thickness_mm", k));
  }
  if (!d.contains("sigma_a") || d.contains("sigma_s") == d.contains("sigma_s_prime"))
    throw Error("material: give a preset name, or sigma_a with one of sigma_s (and g) or sigma_s_prime");
  Material m;
  using namespace argument_ranges;
  m.sigma_a = rgb(d["sigma_a"], kCoefficient, "sigma_a");
  m.sigma_s = d.contains("sigma_s") ? rgb(d["sigma_s"], kCoefficient, "sigma_s")
                                    : rgb(d["sigma_s_prime"], kCoefficient, "sigma_s_prime");
  if (d.contains("g")) m.g = rgb(d["g"], kAnisotropy, "g");
  if (d.contains("eta")) m.eta = static_cast<float>(number_argument(d["eta"], kEta, "eta"));
  // The multipole model's part thickness [mm]; validate_material refuses a negative one.
  if (d.contains("thickness_mm")) m.thickness_mm = static_cast<float>(number_argument(d["thickness_mm"], kPointMm, "thickness_mm"));
  return m;
}

Material material_of(const py::handle& material, const std::string& model, const py::handle& eta) {
  Material m;
  if (py::isinstance<py::str>(material)) {
    const std::string name = py::str(material);
    const MaterialPreset* preset = find_material_preset(name);
    if (!preset) throw Error(fmt::format("material: unknown material '{}' (see: lucent.materials())", name));
    m = material_from_preset(*preset);
  } else if (py::isinstance<py::dict>(material)) {
    m = coefficients(py::reinterpret_borrow<py::dict>(material));
  } else {
    throw Error("material: give a preset name or a dict of coefficients");
  }
  if (!eta.is_none()) m.eta = static_cast<float>(number_argument(eta, argument_ranges::kEta, "eta"));
  const std::optional<BssrdfModel> parsed = parse_bssrdf_model(model);
  if (!parsed)
    throw Error(fmt::format(
        "model: unknown model '{}'; known: directional, standard, photon-beam, better-dipole, tabulated, multipole", model));
  m.model = *parsed;
  validate_material(m, "bssrdf");
  return m;
}

py::dict bssrdf(const py::handle& material, const std::string& model, const py::handle& eta,
                const py::handle& xi, const py::handle& ni, const py::handle& wi, const py::handle& xo,
                const py::handle& no) {
  const Material m = material_of(material, model, eta);
  using argument_ranges::kPointMm;
  const glm::vec3 xi_mm = rgb(xi, kPointMm, "xi"), wi_unit = unit(wi, "wi"), ni_unit = unit(ni, "ni");
  const glm::vec3 xo_mm = rgb(xo, kPointMm, "xo"), no_unit = unit(no, "no");
  auto evaluation = std::make_shared<BssrdfEvaluation>();  // the tabulated model builds its tables first: minutes
  run_abandonable([=] { *evaluation = evaluate_bssrdf(m, xi_mm, wi_unit, ni_unit, xo_mm, no_unit); });
  const BssrdfEvaluation& e = *evaluation;
  py::dict out;
  out["model"] = std::string(to_string(m.model)), out["material"] = m.name, out["eta"] = m.eta;
  out["S_d"] = py::make_tuple(e.S_d.x, e.S_d.y, e.S_d.z), out["T12"] = e.T12, out["units"] = "mm^-2";
  return out;
}

py::dict bssrdf_total(const py::handle& material, const std::string& model, const py::handle& eta,
                      const py::handle& incidence) {
  const double incidence_deg = number_argument(incidence, argument_ranges::kIncidenceDeg, "incidence_deg");
  const Material m = material_of(material, model, eta);
  auto total = std::make_shared<ModelTotalReflectance>();  // seconds (photon-beam), minutes (tabulated, first time)
  run_abandonable([=] { *total = model_total_reflectance(m, incidence_deg); });
  const ModelTotalReflectance& t = *total;
  py::dict out;
  out["model"] = std::string(to_string(m.model)), out["material"] = m.name, out["eta"] = m.eta;
  out["incidence_deg"] = incidence_deg;
  out["total"] = py::make_tuple(t.total.x, t.total.y, t.total.z);
  out["radiosity"] = py::make_tuple(t.radiosity.x, t.radiosity.y, t.radiosity.z);
  out["exit_transmittance"] = t.exit_transmittance;
  return out;
}

}  // namespace

void bind_bssrdf(py::module_& m) {
  m.def("bssrdf", &bssrdf, py::arg("material"), py::kw_only(), py::arg("model") = std::string(lucent::to_string(lucent::kDefaultBssrdfModel)),
        py::arg("eta") = py::none(), py::arg("xi") = py::make_tuple(0, 0, 0), py::arg("ni") = py::make_tuple(0, 0, 1),
        py::arg("wi") = py::make_tuple(0, 0, 1), py::arg("xo") = py::make_tuple(1, 0, 0),
        py::arg("no") = py::make_tuple(0, 0, 1),
        "S_d [mm^-2] per band of a diffusion model as `lucent bssrdf --json` prints it. material: a preset name "
        "(lucent.materials()) or a dict with sigma_a and sigma_s (and g) or sigma_s_prime, each a number or 3 "
        "[mm^-1], and optionally eta; model: standard (the default) | directional | photon-beam | better-dipole | tabulated | multipole; "
        "xi, xo: entry and exit points [mm]; ni, no: their normals; wi: toward the light. Returns {\"model\", "
        "\"material\", \"eta\", \"S_d\", \"T12\", \"units\"}.");
  m.def("bssrdf_total", &bssrdf_total, py::arg("material"), py::kw_only(), py::arg("model") = std::string(lucent::to_string(lucent::kDefaultBssrdfModel)),
        py::arg("eta") = py::none(), py::arg("incidence_deg") = 0.0,
        "The model's flat half-space total diffuse reflectance per refracted power, as `lucent bssrdf --total "
        "--json` prints it: {\"total\", \"radiosity\", \"exit_transmittance\", ...}.");
}

}  // namespace lucent::python
