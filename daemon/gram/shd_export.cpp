// The model's field as a .shd (see shd_export.h).
#include "gram/shd_export.h"

#include <cmath>

namespace acomms::gram {

ShdField shd_field_of(const TransmissionLoss& tl, const Environment& env) {
  if (tl.irregular)
    throw std::invalid_argument(
        "a .shd is written for a rectilinear receiver grid only; this environment's receivers are irregular "
        "(RUNTYPE(5) 'I'): write the CSV instead");
  if (tl.pressure.size() != tl.tl_db.size() || tl.tl_db.size() != tl.range_m.size() * tl.depth_m.size())
    throw std::invalid_argument("the run kept no pressure field: run it with RunOptions::keep_pressure");
  ShdField field;
  field.layout = ShdLayout::k2023;
  field.title = env.title();
  field.plot_type = "rectilin";
  field.freq = {env.frequency_hz()};
  field.theta = {0.0};
  field.sx = {0.0};
  field.sy = {0.0};
  field.source_depth_m = {static_cast<float>(env.source_depth_m())};
  field.receiver_depth_m.assign(tl.depth_m.begin(), tl.depth_m.end());
  field.receiver_range_m = tl.range_m;
  field.pressure.resize(tl.pressure.size());
  // One record per receiver depth, NRr values each: the output order of
  // a rectilinear TransmissionLoss already.
  const bool coherent = env.field_mode() == COHERENT;
  for (std::size_t i = 0; i < tl.pressure.size(); ++i) {
    const std::complex<double> p = tl.pressure[i];
    field.pressure[i] = coherent ? std::complex<float>(static_cast<float>(-p.real()), static_cast<float>(p.imag()))
                                 : std::complex<float>(static_cast<float>(p.real()), 0.0f);  // √intensity
  }
  return field;
}

}  // namespace acomms::gram
