// arguments.h: Python arguments checked against the ranges of the CLI's options (params/argument_ranges.h), with
// the CLI's words: "xo: 1e+300 is out of range; allowed range [-1000000, 1000000] mm" raises lucent.Error.
#pragma once
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "params/number_range.h"

namespace lucent::python {

// A Python number (int, float, numpy scalar) in `range`; a bool or anything else is refused.
double number_argument(const pybind11::handle& value, const NumberRange& range, const std::string& name);
// A Python int (or numpy integer) in `range`, whose bounds lie within [0, 2^64) or [-2^63, 2^63).
unsigned long long whole_argument(const pybind11::handle& value, const NumberRange& range, const std::string& name);
// A number or a sequence of numbers (list, tuple, numpy array), each in `range`.
std::vector<double> numbers_argument(const pybind11::handle& value, const NumberRange& range, const std::string& name);

}  // namespace lucent::python
