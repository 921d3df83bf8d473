#pragma once
// The words of a broken bound: "<name> = <value> must be <rule>", e.g.
// "gram.workers = 0 must be within [1, 64]" or "horizon_s = 0 must be a
// finite number greater than 0".
//
// Errors that reach a person name the field, the value and the bound
// (DESIGN, Conventions), in the same words wherever they are raised; the
// sentence was assembled by hand at each site. The callers keep formatting
// their own numbers (integers with std::to_string, measurements with
// format_number), because the exact text of each existing message is what
// tests and operators already read.
//
// Thread-safe: pure functions.

#include <sstream>
#include <string>
#include <string_view>

namespace acomms::util {

// The shortest form an ostream gives a double ("0.5", "1e+06", "nan").
inline std::string format_number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// "<name> = <value> must be <rule>".
inline std::string must_be(std::string_view name, std::string_view value, std::string_view rule) {
  std::string text(name);
  text += " = ";
  text += value;
  text += " must be ";
  text += rule;
  return text;
}

// The rule "within [low, high]" (both ends included).
inline std::string within(std::string_view low, std::string_view high) {
  std::string text = "within [";
  text += low;
  text += ", ";
  text += high;
  text += "]";
  return text;
}

}  // namespace acomms::util
