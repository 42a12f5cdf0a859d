// number_range.cpp: number ranges as text and the check of one value against its range.
#include "params/number_range.h"

#include <cmath>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent {

std::string bound_text(double x) {
  return std::abs(x) < 1e16 && x == std::floor(x) ? fmt::format("{:.0f}", x) : fmt::format("{:g}", x);
}

std::string range_text(const NumberRange& range) {
  return fmt::format("allowed range [{}, {}]{}", bound_text(range.lo), bound_text(range.hi),
                     range.unit.empty() ? "" : fmt::format(" {}", range.unit));
}

std::string number_problem(double x, const NumberRange& range, std::string_view as_written) {
  const std::string text = as_written.empty() ? fmt::format("{:g}", x) : std::string(as_written);
  if (!std::isfinite(x)) return fmt::format("{} is not a finite number; {}", text, range_text(range));
  if (x < range.lo || x > range.hi) return fmt::format("{} is out of range; {}", text, range_text(range));
  if (range.whole && x != std::floor(x)) return fmt::format("{} is not a whole number", text);
  return {};
}

double checked_number(double x, const NumberRange& range, std::string_view name) {
  const std::string problem = number_problem(x, range);
  if (!problem.empty()) throw Error(fmt::format("{}: {}", name, problem));
  return x;
}

}  // namespace lucent
