// `acommsctl sim mac-discovery`: the output formats, run as a user would.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <unistd.h>

#include "child_process.h"

namespace {

using acomms::testing::lines_of;

std::string log_prefix(const std::string& name) {
  return ::testing::TempDir() + "mac_discovery_" + name + "_" + std::to_string(getpid());
}

TEST(MacDiscoveryCli, Schneider2013Table27Scenario) {
  acomms::testing::RunResult result = acomms::testing::run(
      ACOMMSCTL_BINARY,
      {"sim", "mac-discovery", "--ids", "1,2", "--slot", "15", "--coolness", "3", "--start", "0",
       "--blank-rule", "figure"},
      log_prefix("scenario"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::vector<std::string> lines = lines_of(result.out);
  ASSERT_GE(lines.size(), 10u);
  EXPECT_EQ(lines.back(), "converged_at_s=180 collisions=4");
  // The table: a header, then one row per slot, time first.
  bool header = false;
  for (const std::string& line : lines) header = header || line.rfind("time_s", 0) == 0;
  EXPECT_TRUE(header) << result.out;
  EXPECT_NE(result.out.find("0       00:00:00  send [1 _]"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("COLLISION 1,2"), std::string::npos);
  EXPECT_NE(result.out.find("blank [_ 2] +1"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("4.00 cycles after the last power-on"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("send [1 2 _]"), std::string::npos) << result.out;
}

TEST(MacDiscoveryCli, NeverConverging) {
  acomms::testing::RunResult result = acomms::testing::run(
      ACOMMSCTL_BINARY,
      {"sim", "mac-discovery", "--ids", "12,90,33", "--start", "1000", "--horizon-cycles", "5"},
      log_prefix("never"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(lines_of(result.out).back().rfind("converged_at_s=never collisions=", 0), 0u)
      << result.out;
}

TEST(MacDiscoveryCli, MonteCarloCsv) {
  acomms::testing::RunResult result = acomms::testing::run(
      ACOMMSCTL_BINARY,
      {"sim", "mac-discovery", "--monte-carlo", "--sizes", "3-4", "--coolness", "n+1,2",
       "--p-collide", "1", "--trials", "5"},
      log_prefix("csv"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::vector<std::string> lines = lines_of(result.out);
  ASSERT_EQ(lines.size(), 5u) << result.out;
  EXPECT_EQ(lines[0], "nodes,coolness,p_collide,collision_prob,mean_discovery_slots,fail_pct");
  EXPECT_EQ(lines[1].rfind("3,4,1,", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("3,2,1,", 0), 0u) << lines[2];
  EXPECT_EQ(lines[3].rfind("4,5,1,", 0), 0u) << lines[3];
  for (size_t i = 1; i < lines.size(); ++i)
    EXPECT_EQ(std::count(lines[i].begin(), lines[i].end(), ','), 5) << lines[i];
}

// Users take the defaults, so the default rule must converge: with no
// --blank-rule, under 1 % of random networks of 3-6 nodes may fail at
// coolness = nodes + 1 (the figure rule fails 27-73 % of them).
TEST(MacDiscoveryCli, DefaultRuleConvergesRandomNetworksAtCoolnessNodesPlusOne) {
  acomms::testing::RunResult result = acomms::testing::run(
      ACOMMSCTL_BINARY,
      {"sim", "mac-discovery", "--monte-carlo", "--sizes", "3-6", "--coolness", "4-7", "--p-collide", "1",
       "--trials", "200"},
      log_prefix("default_mc"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::vector<std::string> lines = lines_of(result.out);
  ASSERT_EQ(lines.size(), 17u) << result.out;  // header + 4 sizes x 4 coolness values
  int checked = 0;
  for (size_t i = 1; i < lines.size(); ++i) {
    int nodes = 0, coolness = 0;
    double p_collide = 0, collision_prob = 0, mean_slots = 0, fail_pct = 100;
    ASSERT_EQ(std::sscanf(lines[i].c_str(), "%d,%d,%lf,%lf,%lf,%lf", &nodes, &coolness, &p_collide,
                          &collision_prob, &mean_slots, &fail_pct),
              6)
        << lines[i];
    if (coolness != nodes + 1) continue;
    EXPECT_LT(fail_pct, 1.0) << lines[i];
    ++checked;
  }
  EXPECT_EQ(checked, 4) << result.out;
}

// Schneider (2013)'s two-vehicle example, both powered on together, under
// the default rule: converged within 450 s for coolness 3-6, whatever the
// time of day (the cycle count k enters the blank's placement).
TEST(MacDiscoveryCli, DefaultRuleTwoVehiclesConvergeWithin450Seconds) {
  for (int coolness : {3, 4, 5, 6}) {
    for (int start : {0, 3600, 43200}) {
      acomms::testing::RunResult result = acomms::testing::run(
          ACOMMSCTL_BINARY,
          {"sim", "mac-discovery", "--ids", "1,2", "--slot", "15", "--coolness", std::to_string(coolness),
           "--start", std::to_string(start)},
          log_prefix("default_pair"));
      ASSERT_EQ(result.exit_code, 0) << result.err;
      double converged_at = -1;
      ASSERT_EQ(std::sscanf(lines_of(result.out).back().c_str(), "converged_at_s=%lf", &converged_at), 1)
          << "coolness " << coolness << " start " << start << ": " << lines_of(result.out).back();
      EXPECT_LE(converged_at - start, 450) << "coolness " << coolness << " start " << start;
    }
  }
}

TEST(MacDiscoveryCli, BadUsage) {
  acomms::testing::RunResult no_ids = acomms::testing::run(
      ACOMMSCTL_BINARY, {"sim", "mac-discovery"}, log_prefix("no_ids"));
  EXPECT_EQ(no_ids.exit_code, 2);
  EXPECT_NE(no_ids.err.find("--ids"), std::string::npos) << no_ids.err;
  acomms::testing::RunResult duplicate = acomms::testing::run(
      ACOMMSCTL_BINARY, {"sim", "mac-discovery", "--ids", "3,3"}, log_prefix("dup"));
  EXPECT_EQ(duplicate.exit_code, 2);
  EXPECT_NE(duplicate.err.find("ids must differ"), std::string::npos) << duplicate.err;
  acomms::testing::RunResult range = acomms::testing::run(
      ACOMMSCTL_BINARY, {"sim", "mac-discovery", "--monte-carlo", "--sizes", "x-3"},
      log_prefix("range"));
  EXPECT_EQ(range.exit_code, 2);
}

}  // namespace
