// errors.cpp: lucent::Error arrives in Python as lucent.Error (a RuntimeError) with the one line the CLI prints
// after "lucent: ".
#include "bindings.h"

#include "lucent/error.h"

namespace lucent::python {

void bind_errors(py::module_& m) {
  py::register_exception<Error>(m, "Error", PyExc_RuntimeError);
}

}  // namespace lucent::python
