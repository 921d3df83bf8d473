// CTD CSV reading: columns by name, pressure or depth, conductivity or
// salinity, binning, and errors naming the line and the column.
#include <gtest/gtest.h>

#include "gram/ctd_cast.h"
#include "gram/pressure.h"
#include "gram/salinity.h"
#include "gram/sound_speed.h"

namespace acomms::gram {
namespace {

std::string error_of(const std::string& text) {
  try {
    read_ctd_csv(text, "cast.csv");
  } catch (const ImportError& e) {
    return e.what();
  }
  return "(read)";
}

TEST(GramCtdCast, ReadsPressureAndConductivityColumnsInAnyOrder) {
  const double c = 42.914 * 0.85;  // conductivity ratio 0.85
  const auto cast = read_ctd_csv("p_dbar,lat_deg,conductivity_ms_per_cm,t90_degc\n1000,30," +
                                     std::to_string(c) + ",10\n", "cast.csv");
  ASSERT_EQ(cast.size(), 1u);
  EXPECT_NEAR(cast[0].depth_m, unesco_depth_from_pressure(1000, 30), 1e-9);
  EXPECT_NEAR(cast[0].salinity_psu, practical_salinity(0.85, t68_from_t90(10), 1000), 1e-9);
}

TEST(GramCtdCast, AveragesDownAndUpCastSamplesInADepthBin) {
  const auto cast = read_ctd_csv(
      "depth_m,t90_degc,s_psu,lat_deg\n10,15,35,45\n10.2,15,35,45\n20,10,35,45\n9.9,14,35,45\n",
      "cast.csv");
  const auto profile = sound_speed_from_ctd(cast);
  ASSERT_EQ(profile.size(), 2u);
  EXPECT_NEAR(profile[0].depth_m(), (10 + 10.2 + 9.9) / 3, 1e-12);
  const double mean = (sample_sound_speed(cast[0], SoundSpeedEquation::kUnesco) +
                       sample_sound_speed(cast[1], SoundSpeedEquation::kUnesco) +
                       sample_sound_speed(cast[3], SoundSpeedEquation::kUnesco)) / 3;
  EXPECT_NEAR(profile[0].speed_mps(), mean, 1e-9);
  EXPECT_LT(profile[0].depth_m(), profile[1].depth_m());
}

TEST(GramCtdCast, ErrorsNameTheLineAndTheColumn) {
  EXPECT_EQ(error_of("t90_degc,s_psu,lat_deg\n"), "cast.csv:1: the header has no depth_m or p_dbar column");
  EXPECT_EQ(error_of("depth_m,s_psu,lat_deg\n"), "cast.csv:1: the header has no t90_degc column");
  EXPECT_EQ(error_of("depth_m,t90_degc,s_psu,lat_deg\n0,10,35,45\n5,warm,35,45\n"),
            "cast.csv:3: t90_degc 'warm' is not a number");
  EXPECT_EQ(error_of("depth_m,t90_degc,s_psu,lat_deg\n0,10,35\n"), "cast.csv:2: no value for column lat_deg");
  EXPECT_EQ(error_of("depth_m,t90_degc,s_psu,lat_deg\n-5,10,35,45\n"), "cast.csv:2: depth_m must be within [0, 12000]");
  EXPECT_EQ(error_of("depth_m,t90_degc,s_psu,lat_deg\n"), "cast.csv: no samples");
  EXPECT_EQ(error_of(""), "cast.csv: empty file (a header line is needed)");
}

}  // namespace
}  // namespace acomms::gram
