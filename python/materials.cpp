// materials.cpp: lucent.materials: the measured presets (`lucent materials`), coefficients in mm^-1.
#include "bindings.h"
#include "lucent/error.h"
#include "lucent/material.h"

namespace lucent::python {
namespace {

py::tuple rgb(glm::vec3 v) { return py::make_tuple(v.x, v.y, v.z); }

bool usable(const MaterialPreset& p) {
  try {
    validate_material(material_from_preset(p), p.name);
    return true;
  } catch (const Error&) {
    return false;
  }
}

py::list presets() {
  py::list list;
  for (const MaterialPreset& p : material_presets()) {
    py::dict d;
    d["name"] = p.name, d["sigma_a"] = rgb(p.sigma_a), d["sigma_s"] = rgb(p.sigma_s), d["g"] = rgb(p.g);
    d["eta"] = p.eta, d["reduced"] = p.reduced, d["source"] = p.source, d["note"] = p.note;
    d["usable"] = usable(p);
    list.append(d);
  }
  return list;
}

}  // namespace

void bind_materials(py::module_& m) {
  m.def("materials", &presets,
        "The measured material presets: dicts with name, sigma_a, sigma_s (reduced: sigma_s' with g = 0 where "
        "`reduced`), g, eta, source, note and usable (False: a zero coefficient the diffusion models cannot use).");
}

}  // namespace lucent::python
