// Depth from sea pressure and back.
//
// Problem: the UNESCO sound-speed equation wants sea pressure, vehicles and
// SSP files speak depth. Two published conversions: UNESCO 1983 (Saunders &
// Fofonoff 1976; the default) and Saunders 1981 (closed form both ways,
// within 0.1 % of UNESCO). UNESCO has no closed-form inverse; it is solved
// by Newton iteration to well below a millimetre.
// Thread-safe: pure functions. Spec: shared/spec/gram.md §2.3.
#pragma once

namespace acomms::gram {

// Latitude used when the vehicle's is not known (spec §2.3).
inline constexpr double kDefaultLatitudeDeg = 45.0;

double unesco_depth_from_pressure(double pressure_dbar, double latitude_deg);
double unesco_pressure_from_depth(double depth_m, double latitude_deg);
double saunders_depth_from_pressure(double pressure_dbar, double latitude_deg);
double saunders_pressure_from_depth(double depth_m, double latitude_deg);

}  // namespace acomms::gram
