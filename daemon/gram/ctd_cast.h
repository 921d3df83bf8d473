// A CTD cast, read from CSV, turned into a sound speed profile.
//
// Problem: the sound speed the model needs is measured by vehicles as
// conductivity (or salinity), ITS-90 temperature and pressure (or depth).
// Decision (spec §2.6): each sample is converted — depth ↔ pressure by
// UNESCO 1983 at the sample's latitude, T90 → T68, conductivity → PSS-78
// salinity — and its sound speed computed (UNESCO by default, Mackenzie on
// request); samples are then averaged in depth bins (down- and up-casts
// together), empty bins dropped, so the profile's depths strictly increase.
// CSV columns are found by header name (those of ctd_cast_to_ssp.csv):
// `depth_m` or `p_dbar`, `t90_degc`, `s_psu` or `conductivity_ms_per_cm`,
// `lat_deg`; other columns are ignored. Thread-safe: pure functions.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "acomms/gram/environment.pb.h"
#include "gram/list_directed.h"  // ImportError

namespace acomms::gram {

struct CtdSample {
  double depth_m = 0, pressure_dbar = 0;
  double t90_degc = 0, salinity_psu = 0, latitude_deg = 0;
};

// Throws ImportError naming the file, the line and the column.
std::vector<CtdSample> read_ctd_csv(std::string_view text, const std::string& file_name);

enum class SoundSpeedEquation { kUnesco, kMackenzie };

struct CtdProfileOptions {
  double bin_m = 1.0;
  SoundSpeedEquation equation = SoundSpeedEquation::kUnesco;
};

// One point per non-empty bin: the mean depth and mean sound speed of its samples.
std::vector<SoundSpeedPoint> sound_speed_from_ctd(const std::vector<CtdSample>& cast,
                                                  const CtdProfileOptions& options = {});

// The sound speed of one sample by the chosen equation.
double sample_sound_speed(const CtdSample& s, SoundSpeedEquation equation);

}  // namespace acomms::gram
