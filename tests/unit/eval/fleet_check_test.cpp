// `fleet check` (daemon/eval/fleet_check.h) on tests/fleet/planted, a fleet
// with one planted fault of each kind, each marked by a "# PLANT <kind>
// <which>" comment: every kind is found, at both marked places, and
// nothing else is; and the example fleet passes.

#include <gtest/gtest.h>
#include <unistd.h>

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

// Encryption and next hops, not planted above: a receiver with another
// passphrase (or none) and a route through an id nobody has.
TEST(FleetCheck, AnEncryptedTypeNeedsTheSendersPassphraseAndANextHopANode) {
  const fs::path dir = fs::temp_directory_path() / ("acomms-fleet-check-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string fleet = (dir / "fleet.conf").string();
  std::ofstream(fleet) << "node { name: \"c\" abstract: true config { dccl { proto_files: \""
                       << ACOMMS_SOURCE_DIR << "/examples/messages.proto\" }\n"  // 1
                       << "  mac { name: \"none\" } } }\n"                        // 2
                       << "node { name: \"a\" parent: \"c\" config { driver { modem_id: 1 }\n"  // 3
                       << "  dccl { passphrase: \"secret\" } } keys { passphrase_id: \"ops-2026\" } }\n"  // 4
                       << "node { name: \"b\" parent: \"c\" config { driver { modem_id: 2 }\n"  // 5
                       << "  routing { route { dest: 1 next_hop: 7 } } } }\n";  // 6
  std::vector<FleetFinding> findings = check_fleet(core::Fleet::load(fleet));
  fs::remove_all(dir);
  ASSERT_EQ(findings.size(), 2u);
  EXPECT_EQ(findings[0].kind, "route-dest");
  EXPECT_EQ(core::to_string(findings[0].first), fleet + ":6");
  EXPECT_EQ(core::to_string(findings[0].second), fleet + ":5");
  EXPECT_EQ(findings[1].kind, "key");
  EXPECT_NE(findings[1].message.find("passphrase ops-2026; b has none"), std::string::npos) << findings[1].message;
  EXPECT_EQ(core::to_string(findings[1].first), fleet + ":4");
  EXPECT_EQ(core::to_string(findings[1].second), fleet + ":5");
}

}  // namespace
}  // namespace acomms::eval
