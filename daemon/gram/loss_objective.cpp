// Depth objective eq. 4.3: shared/spec/gram.md §6.2.
#include "gram/loss_objective.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gram/validation_text.h"

namespace acomms::gram {

std::optional<double> window_maximum(std::span<const double> h_bar_db) {
  std::optional<double> m;
  for (double h : h_bar_db)
    if (std::isfinite(h)) m = m ? std::max(*m, h) : h;
  return m;
}

std::vector<double> loss_objective(std::span<const double> h_bar_db, double h_max_db) {
  if (auto e = require_greater("h_max_db", h_max_db, 0.0)) throw std::invalid_argument(*e);
  std::vector<double> o;
  o.reserve(h_bar_db.size());
  for (double h : h_bar_db) o.push_back(std::isnan(h) ? 0.0 : std::max(1.0 - h / h_max_db, 0.0));
  return o;
}

}  // namespace acomms::gram
