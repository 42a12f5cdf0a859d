// option_checks.h: command-line numbers are checked like scene values: finite, within a stated range, whole where
// an integer is meant. CLI11's own Range lets NaN through and converts "-5" to an unsigned 2^64 - 5; these
// validators read the text themselves, so every bad number is one line naming the option:
//   lucent: --photons: -5 is out of range; allowed range [1, 1000000000000]
#pragma once
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "params/number_range.h"

namespace lucent::cli {

// A number in `range` (params/number_range.h, the check the Python module makes too); integers as digits.
inline CLI::Validator number_in(const NumberRange& range) {
  const std::string unit(range.unit);
  const double lo = range.lo, hi = range.hi;
  const bool whole = range.whole;
  const std::string description = range_text(range);
  return CLI::Validator(
      [lo, hi, whole, unit](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        errno = 0;
        double x = std::strtod(begin, &end);
        // Decimal only (strtod also reads hexadecimal "0x10").
        if (end == begin || *end != '\0' || text.find_first_of("xX") != std::string::npos)
          return fmt::format("'{}' is not a number", text);
        if (errno == ERANGE && std::abs(x) < 1.0) x = 0.0;  // underflow: as good as zero
        if (errno == ERANGE) x = std::copysign(HUGE_VAL, x);  // overflow: not finite
        std::string problem = number_problem(x, {lo, hi, false, unit}, text);
        if (!problem.empty()) return problem;
        // Integers as digits: the option's integer conversion reads no fraction or exponent ("1e3", "2.0").
        if (whole && (x != std::floor(x) || text.find_first_of(".eE") != std::string::npos))
          return fmt::format("{} is not a whole number (write digits only)", text);
        return {};
      },
      (whole ? "INT in " : "NUMBER in ") + description);
}

// A number in [lo, hi]; `whole`: also an integer.
inline CLI::Validator number_in(double lo, double hi, bool whole = false, std::string unit = "") {
  return number_in(NumberRange{lo, hi, whole, unit});
}

inline CLI::Validator whole_number_in(double lo, double hi, std::string unit = "") {
  return number_in(lo, hi, true, std::move(unit));
}

// Any number a float holds with room to spare (coordinates, exposures).
inline CLI::Validator finite_number() { return number_in(-1e30, 1e30); }

}  // namespace lucent::cli
