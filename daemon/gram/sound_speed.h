// Sound speed in sea water from temperature, salinity and pressure or depth.
//
// Problem: a vehicle measures temperature, salinity (or conductivity) and
// pressure (or depth); the propagation model needs c(z). Two published
// equations are offered: UNESCO 1983 / Chen & Millero 1977 (the default,
// valid to 1000 bar) and Mackenzie 1981 (nine terms, depth based).
// Invariant: the UNESCO equation is fitted on the IPTS-68 temperature scale,
// so callers holding ITS-90 readings (every modern CTD) convert first with
// t68_from_t90(); the two scales differ by up to 0.015 m/s at 20-40 °C.
// Thread-safe: pure functions. Spec: shared/spec/gram.md §2.1, §2.4, §2.5.
#pragma once

namespace acomms::gram {

// IPTS-68 temperature from an ITS-90 reading (Saunders 1990), °C.
double t68_from_t90(double t90_degc);

// UNESCO 1983 (Chen & Millero 1977) sound speed, m/s. Salinity in PSU,
// temperature IPTS-68 °C, sea pressure in dbar (not bar).
double unesco_sound_speed(double salinity_psu, double t68_degc, double pressure_dbar);

// Mackenzie 1981 nine-term sound speed, m/s: temperature °C, salinity ‰, depth m.
double mackenzie_sound_speed(double t_degc, double salinity_ppt, double depth_m);

}  // namespace acomms::gram
