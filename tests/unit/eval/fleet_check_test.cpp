// `fleet check` (daemon/eval/fleet_check.h) on tests/fleet/planted, a fleet
// with one planted fault of each kind, each marked by a "# PLANT <kind>
// <which>" comment: every kind is found, at both marked places, and
// nothing else is; and the example fleet passes.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "core/fleet.h"
#include "eval/fleet_check.h"

namespace acomms::eval {
namespace {

namespace fs = std::filesystem;

const fs::path kPlanted = fs::path(ACOMMS_SOURCE_DIR) / "tests/fleet/planted";

// "file:line" of the line holding `marker` in the planted fleet's files.
std::string marked(const std::string& marker) {
  for (const char* file : {"fleet.conf", "cruise.conf"}) {
    std::ifstream in(kPlanted / file);
    int number = 0;
    for (std::string line; std::getline(in, line);) {
      ++number;
      if (line.size() >= marker.size() && line.compare(line.size() - marker.size(), marker.size(), marker) == 0) {
        return (kPlanted / file).string() + ":" + std::to_string(number);
      }
    }
  }
  ADD_FAILURE() << "no line ends with " << marker;
  return "";
}

TEST(FleetCheck, FindsEachPlantedFaultAtBothPlacesAndNothingElse) {
  core::Fleet fleet = core::Fleet::load((kPlanted / "fleet.conf").string());
  std::vector<FleetFinding> findings = check_fleet(fleet);
  struct Expected {
    std::string first;
    std::string second;
  };
  const std::map<std::string, Expected> expected = {
      {"dccl-id", {marked("# PLANT dccl-id first"), marked("# PLANT dccl-id second")}},
      {"dccl-version", {marked("# PLANT dccl-version first"), marked("# PLANT dccl-version second")}},
      {"mac-cycle", {marked("# PLANT mac-cycle reference"), marked("# PLANT mac-cycle")}},
      {"slot-source", {marked("# PLANT slot-source"), (kPlanted / "cruise.conf").string() + ":8"}},
      {"modem-id", {marked("# PLANT modem-id first"), marked("# PLANT modem-id second")}},
      {"route-dest", {marked("# PLANT route-dest"), (kPlanted / "fleet.conf").string() + ":7"}},
      {"route-loop", {marked("# PLANT route-loop first"), marked("# PLANT route-loop second")}},
      {"key", {marked("# PLANT key sender"), marked("# PLANT key receiver")}},
      {"slot-short", {marked("# PLANT slot-short seconds"), marked("# PLANT slot-short rate")}},
  };
  std::map<std::string, int> per_kind;
  for (const FleetFinding& finding : findings) {
    ++per_kind[finding.kind];
    auto it = expected.find(finding.kind);
    ASSERT_NE(it, expected.end()) << "unplanted: " << to_string(finding);
    EXPECT_EQ(core::to_string(finding.first), it->second.first) << to_string(finding);
    EXPECT_EQ(core::to_string(finding.second), it->second.second) << to_string(finding);
  }
  for (const auto& [kind, places] : expected) EXPECT_EQ(per_kind[kind], 1) << kind;
}

TEST(FleetCheck, TheExampleFleetMayLaunch) {
  core::Fleet fleet = core::Fleet::load(ACOMMS_SOURCE_DIR "/examples/fleet/fleet.conf");
  ASSERT_EQ(fleet.node_names().size(), 5u);
  std::vector<FleetFinding> findings = check_fleet(fleet);
  for (const FleetFinding& finding : findings) ADD_FAILURE() << to_string(finding);
}

}  // namespace
}  // namespace acomms::eval
