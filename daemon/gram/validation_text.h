// Messages for bad numeric inputs of the depth objective.
//
// Problem: the depth objective is requested at sea; an error must say which
// field is wrong and what bound it broke ("horizon_s = 0 must be greater
// than 0"), in the same words everywhere. Decision: one set of checks that
// return that message (or nullopt); NaN and ±inf fail every bound.
// Thread-safe: pure functions.
#pragma once

#include <optional>
#include <string>

namespace acomms::gram {

std::string format_number(double v);

// `name` = v must be finite and ≥ bound / > bound.
std::optional<std::string> require_at_least(const std::string& name, double v, double bound);
std::optional<std::string> require_greater(const std::string& name, double v, double bound);
// `name` = v must be a finite number.
std::optional<std::string> require_finite(const std::string& name, double v);

}  // namespace acomms::gram
