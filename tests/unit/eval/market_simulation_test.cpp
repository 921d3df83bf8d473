// The marketplace evaluation of Schneider (2013), section 2.3.4
// (daemon/eval/market_simulation.h). `acommsctl sim queue-market` is run as a
// user would in tests/integration/sim_queue_market_cli_test.cpp.

#include "eval/market_simulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace acomms::eval {
namespace {

MarketConfig config_with_ratio(double ratio) {
  MarketConfig config;
  config.tau_s_ratio = ratio;
  return config;
}

MarketPoint at(const MarketConfig& config, double p_empty) {
  return simulate_market(config, {p_empty}).at(0);
}

TEST(MarketSimulation, Schneider2013TableAndGrid) {
  std::vector<MarketMessageType> types = schneider2013_market_types();
  ASSERT_EQ(types.size(), 3u);
  EXPECT_EQ(types[0].value_base, 1);
  EXPECT_EQ(types[0].ttl_s, 1000);
  EXPECT_EQ(types[1].value_base, 2);
  EXPECT_EQ(types[1].ttl_s, 2000);
  EXPECT_EQ(types[2].value_base, 1);
  EXPECT_EQ(types[2].ttl_s, 3000);
  std::vector<double> grid = default_p_empty_grid();
  ASSERT_EQ(grid.size(), 10u);
  EXPECT_EQ(grid.front(), 0.0);
  EXPECT_DOUBLE_EQ(grid.back(), 0.9);
  MarketConfig defaults;
  EXPECT_EQ(defaults.transmissions, 100);
  EXPECT_EQ(defaults.tau_s, 100);
  EXPECT_EQ(defaults.trials, 1000);
  EXPECT_EQ(defaults.tau_s_ratio, 0.1);
}

TEST(MarketSimulation, SameSeedSameNumbers) {
  MarketConfig config = config_with_ratio(1);
  config.trials = 200;
  std::vector<double> grid = default_p_empty_grid();
  std::vector<MarketPoint> a = simulate_market(config, grid);
  std::vector<MarketPoint> b = simulate_market(config, grid);
  ASSERT_EQ(a.size(), grid.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].p_empty, grid[i]);
    EXPECT_EQ(a[i].dynamic, b[i].dynamic);
    EXPECT_EQ(a[i].fixed_value, b[i].fixed_value);
    EXPECT_EQ(a[i].lowest_ttl, b[i].lowest_ttl);
  }
  EXPECT_EQ(format_market_csv(a), format_market_csv(b));

  config.seed += 1;
  std::vector<MarketPoint> other = simulate_market(config, grid);
  EXPECT_NE(other[5].dynamic, a[5].dynamic);  // the seed is used
}

// Common random numbers: a point does not depend on which others are asked for.
TEST(MarketSimulation, PointIndependentOfTheOtherPoints) {
  MarketConfig config = config_with_ratio(0.1);
  config.trials = 100;
  MarketPoint alone = at(config, 0.3);
  MarketPoint within = simulate_market(config, {0.9, 0.3, 0.0}).at(1);
  EXPECT_EQ(alone.dynamic, within.dynamic);
  EXPECT_EQ(alone.fixed_value, within.fixed_value);
  EXPECT_EQ(alone.lowest_ttl, within.lowest_ttl);
}

// Schneider (2013)'s first finding: when variety pays (tau_s = 0.1 tau), the dynamic
// queue scores highest with every queue always full.
TEST(MarketSimulation, DynamicWinsWhenVarietyPays) {
  MarketPoint p = at(config_with_ratio(0.1), 0.0);
  EXPECT_GT(p.dynamic, p.fixed_value);
  EXPECT_GT(p.dynamic, p.lowest_ttl);
}

// Schneider (2013)'s second finding: when variety pays little (tau_s = 10 tau), a
// fixed priority on value_base beats the dynamic queue.
TEST(MarketSimulation, FixedValueWinsWhenVarietyPaysLittle) {
  MarketPoint p = at(config_with_ratio(10), 0.0);
  EXPECT_GT(p.fixed_value, p.dynamic);
}

// With every queue full the static policies always send the same type, so
// their score is known: N (value_base + tau / tau_s) - sum of age / ttl, the
// ages being U[0, tau) (mean tau / 2; the mean over 100 000 draws is within
// 0.5 s of it, far beyond 10 sigma).
TEST(MarketSimulation, StaticPoliciesWithFullQueuesMatchTheClosedForm) {
  for (double ratio : {0.1, 1.0, 10.0}) {
    MarketConfig config = config_with_ratio(ratio);
    MarketPoint p = at(config, 0.0);
    const double n = config.transmissions;
    const double mean_age = config.tau_s / 2;
    // fixed_value: always type 2 (value_base 2, ttl 2000).
    EXPECT_NEAR(p.fixed_value, n * (2 + 1 / ratio) - n * mean_age / 2000, n * 0.5 / 2000) << ratio;
    // lowest_ttl: always type 1 (value_base 1, ttl 1000).
    EXPECT_NEAR(p.lowest_ttl, n * (1 + 1 / ratio) - n * mean_age / 1000, n * 0.5 / 1000) << ratio;
  }
}

// With every queue full the dynamic queue's choices are deterministic: types 1
// and 2 (equal value_base / ttl) alternate and type 3 (a third of that rate)
// comes in when its priority catches up: 1 2 1 2 1 3 2 1 2 1 2 3 ... In 100
// transmissions that is 42, 42 and 16 messages (D_b = 142), last received at
// 9900, 10000 and 9600 s. The gaps of a type add up to its last reception
// time, so D_s = (9900 + 10000 + 9600) / tau_s = 295 / R, and the mean D_e is
// 50 s * (42 / 1000 + 42 / 2000 + 16 / 3000).
TEST(MarketSimulation, DynamicWithFullQueuesMatchesItsSchedule) {
  for (double ratio : {0.1, 1.0, 10.0}) {
    MarketPoint p = at(config_with_ratio(ratio), 0.0);
    const double d_e = 50.0 * (42.0 / 1000 + 42.0 / 2000 + 16.0 / 3000);
    EXPECT_NEAR(p.dynamic, 142 + 295 / ratio - d_e, 0.05) << ratio;
  }
}

TEST(MarketSimulation, NothingSentWhenEveryQueueIsAlwaysEmpty) {
  for (double ratio : {0.1, 10.0}) {
    MarketConfig config = config_with_ratio(ratio);
    config.trials = 10;
    MarketPoint p = at(config, 1.0);
    EXPECT_EQ(p.dynamic, 0.0);
    EXPECT_EQ(p.fixed_value, 0.0);
    EXPECT_EQ(p.lowest_ttl, 0.0);
  }
}

// With a single message type there is nothing to choose: every policy sends
// the same messages and scores the same.
TEST(MarketSimulation, OneTypeLeavesNothingToChoose) {
  MarketConfig config;
  config.types = {{3, 500}};
  config.trials = 50;
  for (double p_empty : {0.0, 0.4, 0.8}) {
    MarketPoint p = at(config, p_empty);
    EXPECT_EQ(p.dynamic, p.fixed_value) << p_empty;
    EXPECT_EQ(p.dynamic, p.lowest_ttl) << p_empty;
    EXPECT_GT(p.dynamic, 0) << p_empty;
  }
}

// Every received message scores at most value_base + gap / tau_s, and the
// gaps of one type add up to at most the trial's length, so a trial's total
// is bounded by N * max(value_base) + (types * N * tau) / tau_s; it is at
// least -N * tau / min(ttl) (D_e alone).
TEST(MarketSimulation, ScoresWithinBounds) {
  MarketConfig config = config_with_ratio(0.5);
  config.trials = 100;
  const double n = config.transmissions;
  const double upper = n * 2 + 3 * n * config.tau_s / (config.tau_s_ratio * config.tau_s);
  const double lower = -n * config.tau_s / 1000;
  for (const MarketPoint& p : simulate_market(config, default_p_empty_grid())) {
    for (double score : {p.dynamic, p.fixed_value, p.lowest_ttl}) {
      EXPECT_LE(score, upper) << p.p_empty;
      EXPECT_GE(score, lower) << p.p_empty;
    }
  }
}

TEST(MarketSimulation, RefusesUnusableConfig) {
  MarketConfig config;
  EXPECT_THROW(simulate_market(config, {1.5}), std::invalid_argument);
  EXPECT_THROW(simulate_market(config, {-0.1}), std::invalid_argument);
  config.tau_s_ratio = 0;
  EXPECT_THROW(simulate_market(config, {0.0}), std::invalid_argument);
  config = MarketConfig{};
  config.trials = 0;
  EXPECT_THROW(simulate_market(config, {0.0}), std::invalid_argument);
  config = MarketConfig{};
  config.types = {{1, 0}};
  EXPECT_THROW(simulate_market(config, {0.0}), std::invalid_argument);
  config = MarketConfig{};
  config.types.clear();
  EXPECT_THROW(simulate_market(config, {0.0}), std::invalid_argument);
}

TEST(MarketSimulation, CsvFormat) {
  std::string csv = format_market_csv({{0, 3088.58154, 1197.5, 1094.99741}, {0.1, 1, 2, 3}});
  EXPECT_EQ(csv,
            "p_empty,dynamic,fixed_value,lowest_ttl\n"
            "0,3088.5815,1197.5000,1094.9974\n"
            "0.1,1.0000,2.0000,3.0000\n");
}

}  // namespace
}  // namespace acomms::eval
