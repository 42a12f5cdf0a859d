// json_values.cpp: Python values as JSON text for scene overrides.
#include "bindings.h"

namespace lucent::python {

std::string to_json_text(const py::handle& value) {
  // numpy arrays and scalars, at any depth, as lists and numbers; anything else json cannot write is a TypeError.
  py::cpp_function plain([](const py::object& o) -> py::object {
    if (py::hasattr(o, "tolist")) return o.attr("tolist")();
    throw py::type_error("cannot write a " + py::str(py::type::of(o)).cast<std::string>() + " as a scene value");
  });
  return py::module_::import("json").attr("dumps")(value, py::arg("default") = plain).cast<std::string>();
}

}  // namespace lucent::python
