// The example cast of ctd_cast_to_ssp.csv, read as a user's CSV file, gives
// the tabulated sound speeds by both equations (5e-4 m/s).
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "csv_table.h"
#include "gram/ctd_cast.h"

namespace acomms::gram {
namespace {

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

TEST(GramCtdCast, TheExampleCastGivesTheTabulatedProfileByBothEquations) {
  const std::string path = test::conformance_path("ctd_cast_to_ssp.csv");
  const test::CsvTable table("ctd_cast_to_ssp.csv");
  const auto cast = read_ctd_csv(file_text(path), path);
  ASSERT_EQ(cast.size(), table.size());
  const auto unesco = sound_speed_from_ctd(cast);
  const auto mackenzie = sound_speed_from_ctd(cast, {1.0, SoundSpeedEquation::kMackenzie});
  ASSERT_EQ(unesco.size(), table.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    EXPECT_NEAR(cast[i].pressure_dbar, table.at(i, "p_dbar_unesco"), 5e-4);
    EXPECT_DOUBLE_EQ(unesco[i].depth_m(), table.at(i, "depth_m"));
    EXPECT_NEAR(unesco[i].speed_mps(), table.at(i, "c_chen_millero_mps"), 5e-4) << "row " << i;
    EXPECT_NEAR(mackenzie[i].speed_mps(), table.at(i, "c_mackenzie_mps"), 5e-4) << "row " << i;
  }
}

}  // namespace
}  // namespace acomms::gram
