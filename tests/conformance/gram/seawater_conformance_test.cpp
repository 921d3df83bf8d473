// Sea-water functions against shared/conformance/gram (README §1 tolerances):
// sound speed 5e-4 m/s, depth/pressure 5e-4 m or dbar, salinity 1e-5,
// absorption 1e-6 relative (plus half a unit of the printed last digit),
// noise PSD 1e-3 dB, band levels 0.01 dB.
#include <cmath>

#include <gtest/gtest.h>

#include "csv_table.h"
#include "gram/absorption.h"
#include "gram/ambient_noise.h"
#include "gram/pressure.h"
#include "gram/salinity.h"
#include "gram/sound_speed.h"

namespace acomms::gram {
namespace {

using test::CsvTable;

TEST(GramSeawater, UnescoSoundSpeedMatchesTheTableIncludingTheCheckValue) {
  CsvTable t("soundspeed_unesco.csv");
  ASSERT_GT(t.size(), 400u);
  for (std::size_t i = 0; i < t.size(); ++i)
    EXPECT_NEAR(unesco_sound_speed(t.at(i, "s_psu"), t.at(i, "t68_degc"), t.at(i, "p_dbar")),
                t.at(i, "c_mps"), 5e-4) << "row " << i;
}

TEST(GramSeawater, Its90ReadingsAreConvertedToIpts68BeforeTheUnescoEquation) {
  CsvTable t("soundspeed_unesco_its90.csv");
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double t90 = t.at(i, "t90_degc");
    EXPECT_NEAR(t68_from_t90(t90), t.at(i, "t68_degc"), 5e-6);
    EXPECT_NEAR(unesco_sound_speed(t.at(i, "s_psu"), t68_from_t90(t90), t.at(i, "p_dbar")),
                t.at(i, "c_mps"), 5e-4) << "row " << i;
    EXPECT_NEAR(unesco_sound_speed(t.at(i, "s_psu"), t90, t.at(i, "p_dbar")),
                t.at(i, "c_mps_if_t90_used_unconverted"), 5e-4) << "row " << i;
  }
}

TEST(GramSeawater, MackenzieSoundSpeedMatchesTheTable) {
  CsvTable t("soundspeed_mackenzie.csv");
  ASSERT_GT(t.size(), 100u);
  for (std::size_t i = 0; i < t.size(); ++i)
    EXPECT_NEAR(mackenzie_sound_speed(t.at(i, "t_degc"), t.at(i, "s_ppt"), t.at(i, "depth_m")),
                t.at(i, "c_mps"), 5e-4) << "row " << i;
}

TEST(GramSeawater, DepthFromPressureByUnescoAndSaunders) {
  CsvTable t("depth_from_pressure.csv");
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double lat = t.at(i, "lat_deg"), p = t.at(i, "p_dbar");
    EXPECT_NEAR(unesco_depth_from_pressure(p, lat), t.at(i, "depth_unesco1983_m"), 5e-4);
    EXPECT_NEAR(saunders_depth_from_pressure(p, lat), t.at(i, "depth_saunders1981_m"), 5e-4);
  }
}

TEST(GramSeawater, PressureFromDepthInvertsBothConversions) {
  CsvTable t("pressure_from_depth.csv");
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double lat = t.at(i, "lat_deg"), z = t.at(i, "depth_m");
    EXPECT_NEAR(unesco_pressure_from_depth(z, lat), t.at(i, "p_dbar_unesco1983_inverse"), 5e-4);
    EXPECT_NEAR(saunders_pressure_from_depth(z, lat), t.at(i, "p_dbar_saunders1981_inverse"),
                5e-4);
  }
}

TEST(GramSeawater, PracticalSalinityFromConductivityRatio) {
  CsvTable t("salinity_pss78.csv");
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double r = t.at(i, "cond_ratio"), temp = t.at(i, "t68_degc"), p = t.at(i, "p_dbar");
    // A ratio printed with 5 or more decimals is rounded (the UNESCO check
    // 1.888091 is printed 1.88809): allow for that rounding through dS/dR.
    const double rounding = t.half_unit(i, "cond_ratio") >= 5e-5
                                ? 0.0
                                : t.half_unit(i, "cond_ratio") *
                                      std::abs(practical_salinity(r + 1e-4, temp, p) -
                                               practical_salinity(r - 1e-4, temp, p)) / 2e-4;
    EXPECT_NEAR(practical_salinity(r, temp, p), t.at(i, "s_psu"), 1e-5 + rounding) << "row " << i;
  }
}

// The tables print 6 decimals: allow 1e-6 relative plus half a printed unit.
void expect_absorption(double got, double want, std::size_t row) {
  EXPECT_NEAR(got, want, 1e-6 * std::abs(want) + 5.001e-7) << "row " << row;
}

TEST(GramSeawater, ThorpAbsorptionBothForms) {
  CsvTable t("absorption_thorp.csv");
  for (std::size_t i = 0; i < t.size(); ++i) {
    expect_absorption(thorp_absorption(t.at(i, "f_khz")), t.at(i, "alpha_db_per_km_jensen2011"), i);
    expect_absorption(thorp_absorption_stojanovic(t.at(i, "f_khz")),
                      t.at(i, "alpha_db_per_km_stojanovic2007"), i);
  }
}

TEST(GramSeawater, FrancoisGarrisonAbsorptionAndItsThreeTerms) {
  CsvTable t("absorption_francois_garrison.csv");
  ASSERT_GT(t.size(), 500u);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const auto a = francois_garrison_absorption(t.at(i, "f_khz"), t.at(i, "t_degc"),
                                                t.at(i, "s_ppt"), t.at(i, "ph"), t.at(i, "depth_m"));
    expect_absorption(a.total(), t.at(i, "alpha_db_per_km"), i);
    expect_absorption(a.boric_db_per_km, t.at(i, "boric_db_per_km"), i);
    expect_absorption(a.mgso4_db_per_km, t.at(i, "mgso4_db_per_km"), i);
    expect_absorption(a.water_db_per_km, t.at(i, "water_db_per_km"), i);
  }
}

TEST(GramSeawater, AmbientNoisePsdComponentsAndTotal) {
  CsvTable t("ambient_noise_psd.csv");
  for (std::size_t i = 0; i < t.size(); ++i) {
    const auto n = ambient_noise_psd(t.at(i, "f_khz"), t.at(i, "shipping"), t.at(i, "wind_mps"));
    EXPECT_NEAR(n.turbulence_db, t.at(i, "turbulence_db"), 1e-3) << "row " << i;
    EXPECT_NEAR(n.shipping_db, t.at(i, "shipping_db"), 1e-3) << "row " << i;
    EXPECT_NEAR(n.wind_db, t.at(i, "wind_db"), 1e-3) << "row " << i;
    EXPECT_NEAR(n.thermal_db, t.at(i, "thermal_db"), 1e-3) << "row " << i;
    EXPECT_NEAR(n.total_db, t.at(i, "total_db"), 1e-3) << "row " << i;
  }
}

TEST(GramSeawater, AmbientNoiseBandLevel) {
  CsvTable t("ambient_noise_band.csv");
  for (std::size_t i = 0; i < t.size(); ++i)
    EXPECT_NEAR(ambient_noise_band_level(t.at(i, "f_lo_khz"), t.at(i, "f_hi_khz"),
                                         t.at(i, "shipping"), t.at(i, "wind_mps")),
                t.at(i, "nl_db_re_1upa"), 0.01) << "row " << i;
}

TEST(GramSeawater, CtdCastSamplesGiveTheTabulatedPressureTemperatureAndSpeeds) {
  CsvTable t("ctd_cast_to_ssp.csv");
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double p = unesco_pressure_from_depth(t.at(i, "depth_m"), t.at(i, "lat_deg"));
    const double t68 = t68_from_t90(t.at(i, "t90_degc"));
    EXPECT_NEAR(p, t.at(i, "p_dbar_unesco"), 5e-4) << "row " << i;
    EXPECT_NEAR(t68, t.at(i, "t68_degc"), 5e-6) << "row " << i;
    EXPECT_NEAR(unesco_sound_speed(t.at(i, "s_psu"), t68, p), t.at(i, "c_chen_millero_mps"), 5e-4);
    EXPECT_NEAR(mackenzie_sound_speed(t.at(i, "t90_degc"), t.at(i, "s_psu"), t.at(i, "depth_m")),
                t.at(i, "c_mackenzie_mps"), 5e-4) << "row " << i;
  }
}

}  // namespace
}  // namespace acomms::gram
