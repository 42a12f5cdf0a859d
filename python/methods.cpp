// methods.cpp: lucent.methods: every registered method with its parameters, passes and statistics, the list
// `lucent methods --json` prints.
#include "bindings.h"
#include "methods/method_catalog.h"

namespace lucent::python {

void bind_methods(py::module_& m) {
  m.def(
      "methods", [] { return to_python(methods::method_catalog_json()); },
      "The registered methods, the default first: a list of dicts with name, summary, default, "
      "needs_texture_atlas, reference_tolerance, params (name, type, default, unit, min/max or choices, update, "
      "doc), passes and stats.");
}

}  // namespace lucent::python
