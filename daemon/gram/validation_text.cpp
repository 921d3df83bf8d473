// Messages for bad numeric inputs (see validation_text.h).
#include "gram/validation_text.h"

#include <cmath>
#include <sstream>

namespace acomms::gram {

std::string format_number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::optional<std::string> require_at_least(const std::string& name, double v, double bound) {
  if (std::isfinite(v) && v >= bound) return std::nullopt;
  return name + " = " + format_number(v) + " must be a finite number of at least " +
         format_number(bound);
}

std::optional<std::string> require_greater(const std::string& name, double v, double bound) {
  if (std::isfinite(v) && v > bound) return std::nullopt;
  return name + " = " + format_number(v) + " must be a finite number greater than " +
         format_number(bound);
}

std::optional<std::string> require_finite(const std::string& name, double v) {
  if (std::isfinite(v)) return std::nullopt;
  return name + " = " + format_number(v) + " must be a finite number";
}

}  // namespace acomms::gram
