// `acommsctl sim queue-market` run as a user would: the same numbers as the
// marketplace library (daemon/eval/market_simulation.h) with the same
// options, deterministic, and exit code 2 for bad usage.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "child_process.h"
#include "eval/market_simulation.h"

namespace acomms::eval {
namespace {

MarketConfig config_with_ratio(double ratio) {
  MarketConfig config;
  config.tau_s_ratio = ratio;
  return config;
}

// `acommsctl sim queue-market` as a user runs it.
class QueueMarketCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("market_sim_test_" + std::to_string(::getpid()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  acomms::testing::RunResult sim(std::vector<std::string> args) {
    args.insert(args.begin(), {"sim", "queue-market"});
    return acomms::testing::run(ACOMMSCTL_BINARY, args, (dir_ / "ctl").string());
  }

  std::filesystem::path dir_;
};

TEST_F(QueueMarketCommand, PrintsHeaderAndOneLinePerPoint) {
  acomms::testing::RunResult result = sim({"--tau-s-ratio", "0.1"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::vector<std::string> out = acomms::testing::lines_of(result.out);
  ASSERT_EQ(out.size(), 11u) << result.out;
  EXPECT_EQ(out[0], "p_empty,dynamic,fixed_value,lowest_ttl");
  EXPECT_EQ(out[1].rfind("0,", 0), 0u) << out[1];
  EXPECT_EQ(out[10].rfind("0.9,", 0), 0u) << out[10];
  // The same numbers as the library with the same defaults.
  MarketConfig config = config_with_ratio(0.1);
  EXPECT_EQ(result.out, format_market_csv(simulate_market(config, default_p_empty_grid())));
  // And the same again: deterministic.
  EXPECT_EQ(sim({"--tau-s-ratio", "0.1"}).out, result.out);
}

TEST_F(QueueMarketCommand, HonoursItsOptions) {
  acomms::testing::RunResult result =
      sim({"--tau-s-ratio", "10", "--trials", "20", "--seed", "5", "--p-empty", "0,0.5,1",
           "--transmissions", "30", "--tau", "60"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  MarketConfig config = config_with_ratio(10);
  config.trials = 20;
  config.seed = 5;
  config.transmissions = 30;
  config.tau_s = 60;
  EXPECT_EQ(result.out, format_market_csv(simulate_market(config, {0, 0.5, 1})));
  EXPECT_EQ(acomms::testing::lines_of(result.out).back(), "1,0.0000,0.0000,0.0000");
}

TEST_F(QueueMarketCommand, BadUsageExitsTwo) {
  EXPECT_EQ(sim({"--p-empty", "1.5"}).exit_code, 2);
  EXPECT_EQ(sim({"--tau-s-ratio", "0"}).exit_code, 2);
  EXPECT_EQ(sim({"--trials", "0"}).exit_code, 2);
  EXPECT_EQ(acomms::testing::run(ACOMMSCTL_BINARY, {"sim"}, (dir_ / "bare").string()).exit_code, 2);
}

}  // namespace
}  // namespace acomms::eval
