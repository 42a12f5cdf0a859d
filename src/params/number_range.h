// number_range.h: the range a number given by a person must lie in (a command-line option, a Python argument),
// stated as people write it, and the one check behind both: finite, within [lo, hi], whole where an integer is
// meant. The CLI's validators (apps/lucent/option_checks.h) and the Python module call these, so both refuse the
// same values with the same words:
//   --xo: 1e+300 is out of range; allowed range [-1000000, 1000000] mm
#pragma once
#include <string>
#include <string_view>

namespace lucent {

struct NumberRange {
  double lo = 0.0, hi = 0.0;  // inclusive bounds
  bool whole = false;         // an integer is meant
  std::string_view unit;      // "mm", "degrees"; empty: none
};

// A bound as people write it: 4294967295, not 4.29497e+09; 1e+30.
std::string bound_text(double x);
// "allowed range [lo, hi] unit".
std::string range_text(const NumberRange& range);
// Empty when `x` is acceptable; else why not, without the name: "nan is not a finite number; allowed range [...]",
// "5 is out of range; allowed range [1, 3]", "2.5 is not a whole number". `as_written`: the value as the person
// wrote it (the command line's text); empty: `x` printed.
std::string number_problem(double x, const NumberRange& range, std::string_view as_written = {});
// `x` when acceptable; else throws lucent::Error "<name>: <problem>".
double checked_number(double x, const NumberRange& range, std::string_view name);

}  // namespace lucent
