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

namespace lucent::cli {

// A number in [lo, hi]; `whole`: also an integer (no fraction, no exponent beyond the range).
// A bound as people write it: 4294967295, not 4.29497e+09.
inline std::string bound_text(double x) {
  return std::abs(x) < 1e16 && x == std::floor(x) ? fmt::format("{:.0f}", x) : fmt::format("{:g}", x);
}

inline CLI::Validator number_in(double lo, double hi, bool whole = false, std::string unit = "") {
  std::string range = lo <= -1e30 && hi >= 1e30
                          ? std::string("any finite number")
                          : fmt::format("allowed range [{}, {}]{}", bound_text(lo), bound_text(hi), unit.empty() ? "" : " " + unit);
  return CLI::Validator(
      [lo, hi, whole, range](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        errno = 0;
        double x = std::strtod(begin, &end);
        // Decimal only (strtod also reads hexadecimal "0x10").
        if (end == begin || *end != '\0' || text.find_first_of("xX") != std::string::npos)
          return fmt::format("'{}' is not a number", text);
        if (errno == ERANGE && std::abs(x) < 1.0) x = 0.0;  // underflow: as good as zero
        if (!std::isfinite(x) || errno == ERANGE) return fmt::format("{} is not a finite number; {}", text, range);
        if (x < lo || x > hi) return fmt::format("{} is out of range; {}", text, range);
        // Integers as digits: the option's integer conversion reads no fraction or exponent ("1e3", "2.0").
        if (whole && (x != std::floor(x) || text.find_first_of(".eE") != std::string::npos))
          return fmt::format("{} is not a whole number (write digits only)", text);
        return {};
      },
      whole ? "INT in " + range : "NUMBER in " + range);
}

inline CLI::Validator whole_number_in(double lo, double hi, std::string unit = "") {
  return number_in(lo, hi, true, std::move(unit));
}

// Any finite number (coordinates, exposures).
inline CLI::Validator finite_number() { return number_in(-1e30, 1e30); }

}  // namespace lucent::cli
