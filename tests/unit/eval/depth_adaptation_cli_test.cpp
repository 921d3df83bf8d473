// `acommsctl sim depth-adaptation` run as a user would, on the shipped
// GLINT10-like example (examples/glint10.env) with the defaults: buoy at
// 30 m, vehicle out to 3 km and back at 1.5 m/s, a rate-0 packet every 30 s,
// fixed depths 10..90 m against the adaptive strategy. The thesis's claim
// holds there: adapting receives more than every fixed depth, in the draws
// and in the model's expectation. The values are the run's (seeded,
// deterministic); the bands allow for last-bit differences between builds.
#include <gtest/gtest.h>

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <string>

#include "child_process.h"

namespace {

const std::string kGlint10 = ACOMMS_SOURCE_DIR "/examples/glint10.env";

std::string log_prefix(const std::string& name) {
  return ::testing::TempDir() + "depth_adaptation_cli_" + name + "_" + std::to_string(getpid());
}

struct Strategy {
  double receipt = 0, expected = 0;
  std::vector<double> bins;
};

TEST(DepthAdaptationCli, OnTheGlint10ExampleAdaptingBeatsEveryFixedDepth) {
  const std::string png = ::testing::TempDir() + "glint10_" + std::to_string(getpid()) + ".png";
  const auto result = acomms::testing::run(
      ACOMMSCTL_BINARY, {"--json", "sim", "depth-adaptation", "--env", kGlint10, "--png", png}, log_prefix("glint10"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  google::protobuf::Struct json;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(result.out, &json).ok()) << result.out;
  const auto& fields = json.fields();
  EXPECT_EQ(fields.at("bin_edges_m").list_value().values_size(), 9);  // 8 bins of 400 m to 3.2 km
  std::map<std::string, Strategy> by_name;
  for (const auto& v : fields.at("strategies").list_value().values()) {
    const auto& s = v.struct_value().fields();
    Strategy strategy{s.at("receipt_overall").number_value(), s.at("expected_overall").number_value(), {}};
    for (const auto& b : s.at("receipt").list_value().values()) strategy.bins.push_back(b.number_value());
    by_name[s.at("name").string_value()] = strategy;
  }
  ASSERT_EQ(by_name.size(), 6u) << result.out;
  const Strategy adaptive = by_name.at("adaptive");
  for (const char* fixed : {"10 m", "30 m", "50 m", "70 m", "90 m"}) {
    EXPECT_GT(adaptive.receipt, by_name.at(fixed).receipt) << fixed;
    EXPECT_GT(adaptive.expected, by_name.at(fixed).expected) << fixed;
  }
  EXPECT_TRUE(fields.at("adaptive_beats_every_fixed").bool_value());
  EXPECT_TRUE(fields.at("adaptive_expected_beats_every_fixed").bool_value());
  // The run's values (see the README's table).
  EXPECT_NEAR(adaptive.receipt, ADAPTIVE_RECEIPT, 0.01);
  EXPECT_NEAR(by_name.at("10 m").receipt, FIXED10_RECEIPT, 0.01);
  EXPECT_NEAR(by_name.at("50 m").receipt, FIXED50_RECEIPT, 0.01);
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
  std::filesystem::remove(png);
}

TEST(DepthAdaptationCli, AnEnvironmentThatDoesNotExistIsNamed) {
  const auto result =
      acomms::testing::run(ACOMMSCTL_BINARY, {"sim", "depth-adaptation", "--env", "/nonexistent/x.env"}, log_prefix("missing"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.err.find("/nonexistent/x.env"), std::string::npos) << result.err;
}

}  // namespace
