// Messages for bad numeric inputs (see validation_text.h).
#include "gram/validation_text.h"

#include <cmath>

#include "util/bound_text.h"

namespace acomms::gram {

std::string format_number(double v) { return util::format_number(v); }

std::optional<std::string> require_at_least(const std::string& name, double v, double bound) {
  if (std::isfinite(v) && v >= bound) return std::nullopt;
  return util::must_be(name, format_number(v), "a finite number of at least " + format_number(bound));
}

std::optional<std::string> require_greater(const std::string& name, double v, double bound) {
  if (std::isfinite(v) && v > bound) return std::nullopt;
  return util::must_be(name, format_number(v), "a finite number greater than " + format_number(bound));
}

std::optional<std::string> require_finite(const std::string& name, double v) {
  if (std::isfinite(v)) return std::nullopt;
  return util::must_be(name, format_number(v), "a finite number");
}

}  // namespace acomms::gram
