// arguments.cpp: Python numbers checked as the CLI checks its options' text.
#include "arguments.h"

#include <fmt/format.h>

#include "bindings.h"
#include "lucent/error.h"

namespace lucent::python {
namespace {

std::string text_of(const py::handle& value) { return py::repr(value).cast<std::string>(); }

bool is_bool(const py::handle& value) {
  return py::isinstance<py::bool_>(value) ||
         py::str(py::type::of(value).attr("__name__")).cast<std::string>() == "bool_";  // numpy.bool_
}

}  // namespace

double number_argument(const py::handle& value, const NumberRange& range, const std::string& name) {
  if (is_bool(value) || py::isinstance<py::str>(value) || !PyNumber_Check(value.ptr()))
    throw Error(fmt::format("{}: expected a number, got {}", name, text_of(value)));
  double x = PyFloat_AsDouble(value.ptr());
  if (x == -1.0 && PyErr_Occurred()) {
    // An int beyond a double's range (OverflowError) is out of range; anything else is no number.
    const bool overflow = PyErr_ExceptionMatches(PyExc_OverflowError);
    PyErr_Clear();
    if (!overflow) throw Error(fmt::format("{}: expected a number, got {}", name, text_of(value)));
    throw Error(fmt::format("{}: {} is out of range; {}", name, text_of(value), range_text(range)));
  }
  const std::string problem = number_problem(x, range, py::isinstance<py::int_>(value) ? text_of(value) : "");
  if (!problem.empty()) throw Error(fmt::format("{}: {}", name, problem));
  return x;
}

unsigned long long whole_argument(const py::handle& value, const NumberRange& range, const std::string& name) {
  // Integers only, as the CLI takes digits only: 2.0 and 1e3 are floats.
  if (is_bool(value) || !py::hasattr(value, "__index__")) {
    if (!is_bool(value) && PyNumber_Check(value.ptr()) && !py::isinstance<py::str>(value)) {
      number_argument(value, {range.lo, range.hi, false, range.unit}, name);  // NaN, out of range: say so first
      throw Error(fmt::format("{}: expected an int, got {}", name, text_of(value)));
    }
    throw Error(fmt::format("{}: expected a whole number, got {}", name, text_of(value)));
  }
  const py::int_ integer = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
  if (!integer) throw py::error_already_set();
  number_argument(integer, {range.lo, range.hi, false, range.unit}, name);
  // Exact now that the value lies in the range.
  if (range.lo < 0) return static_cast<unsigned long long>(integer.cast<long long>());
  return integer.cast<unsigned long long>();
}

std::vector<double> numbers_argument(const py::handle& value, const NumberRange& range, const std::string& name) {
  py::object items = py::reinterpret_borrow<py::object>(value);
  if (py::hasattr(value, "tolist")) items = value.attr("tolist")();  // numpy arrays and scalars
  std::vector<double> out;
  if (py::isinstance<py::sequence>(items) && !py::isinstance<py::str>(items)) {
    for (const py::handle item : items) out.push_back(number_argument(item, range, name));
  } else {
    out.push_back(number_argument(items, range, name));
  }
  return out;
}

}  // namespace lucent::python
