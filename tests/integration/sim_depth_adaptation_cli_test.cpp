// `acommsctl sim depth-adaptation` run as a user would, on the shipped
// GLINT10-like example (examples/glint10.env) with the defaults: buoy at
// 30 m, vehicle out to 3 km and back at 1.5 m/s, a rate-0 packet every 30 s,
// fixed depths 10..90 m against the adaptive strategy.
// What the model says there, and what these tests hold it to: with SL 190 dB
// and the noise model at sea state 2 over 4160 Hz (NL 69.9 dB), TL stays
// below 80 dB out to 3 km at every depth, so SNR > 40 dB: every packet
// decodes at every depth and adapting CANNOT help; the command says so.
// With the margin taken away (NL 106 dB, e.g. a vehicle's self-noise), the
// link fails beyond 2 km and the adaptive vehicle receives more than every
// fixed depth, narrowly over 90 m and clearly over 10 m (above the
// thermocline). The values are the runs' (seeded, deterministic); the bands
// allow for last-bit differences between builds.
#include <gtest/gtest.h>

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
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

std::map<std::string, Strategy> run_glint10(const std::vector<std::string>& extra, google::protobuf::Struct& json,
                                            const std::string& name) {
  std::vector<std::string> args = {"--json", "sim", "depth-adaptation", "--env", kGlint10};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto result = acomms::testing::run(ACOMMSCTL_BINARY, args, log_prefix(name));
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(result.out, &json).ok()) << result.out;
  std::map<std::string, Strategy> by_name;
  for (const auto& v : json.fields().at("strategies").list_value().values()) {
    const auto& s = v.struct_value().fields();
    Strategy strategy{s.at("receipt_overall").number_value(), s.at("expected_overall").number_value(), {}};
    for (const auto& b : s.at("receipt").list_value().values()) strategy.bins.push_back(b.number_value());
    by_name[s.at("name").string_value()] = strategy;
  }
  EXPECT_EQ(by_name.size(), 6u) << result.out;
  EXPECT_EQ(json.fields().at("bin_edges_m").list_value().values_size(), 9);  // 8 bins of 400 m to 3.2 km
  return by_name;
}

const char* const kFixed[] = {"10 m", "30 m", "50 m", "70 m", "90 m"};

TEST(DepthAdaptationCli, OnTheGlint10ExampleEveryPacketDecodesAtEveryDepthSoAdaptingCannotHelp) {
  const std::string png = ::testing::TempDir() + "glint10_" + std::to_string(getpid()) + ".png";
  google::protobuf::Struct json;
  const auto by_name = run_glint10({"--png", png}, json, "glint10");
  ASSERT_EQ(by_name.size(), 6u);
  EXPECT_NEAR(json.fields().at("noise_level_db").number_value(), 69.9, 0.05);
  for (const auto& [name, s] : by_name) {
    EXPECT_EQ(s.receipt, 1.0) << name;
    EXPECT_GT(s.expected, 0.99999) << name;
  }
  EXPECT_FALSE(json.fields().at("adaptive_beats_every_fixed").bool_value());
  EXPECT_FALSE(json.fields().at("adaptive_expected_beats_every_fixed").bool_value());
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
  std::filesystem::remove(png);
}

TEST(DepthAdaptationCli, OnTheGlint10ExampleWithoutTheMarginAdaptingBeatsEveryFixedDepth) {
  google::protobuf::Struct json;
  const auto by_name = run_glint10({"--noise-level", "106"}, json, "glint10_nl106");
  ASSERT_EQ(by_name.size(), 6u);
  const Strategy adaptive = by_name.at("adaptive");
  for (const char* fixed : kFixed) {
    EXPECT_GT(adaptive.receipt, by_name.at(fixed).receipt) << fixed;
    EXPECT_GT(adaptive.expected, by_name.at(fixed).expected) << fixed;
  }
  EXPECT_TRUE(json.fields().at("adaptive_beats_every_fixed").bool_value());
  EXPECT_TRUE(json.fields().at("adaptive_expected_beats_every_fixed").bool_value());
  EXPECT_NEAR(adaptive.receipt, 0.904, 0.002);
  EXPECT_NEAR(by_name.at("90 m").receipt, 0.900, 0.002);
  EXPECT_NEAR(by_name.at("50 m").receipt, 0.869, 0.002);
  EXPECT_NEAR(by_name.at("10 m").receipt, 0.781, 0.002);
  // Everything decodes out to 2 km; the edge is in the last bins.
  for (std::size_t b = 0; b < 5; ++b) EXPECT_EQ(adaptive.bins[b], 1.0) << "bin " << b;
  EXPECT_LT(by_name.at("10 m").bins[7], 0.05);
}

TEST(DepthAdaptationCli, AnEnvironmentThatDoesNotExistIsNamed) {
  const auto result =
      acomms::testing::run(ACOMMSCTL_BINARY, {"sim", "depth-adaptation", "--env", "/nonexistent/x.env"}, log_prefix("missing"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.err.find("/nonexistent/x.env"), std::string::npos) << result.err;
}

TEST(DepthAdaptationCli, WorksOnADeepLowFrequencyEnvironmentAUserBrings) {
  // 1000 m of isovelocity water at 500 Hz: another depth, another
  // frequency; the noise band and the grid follow them.
  const std::string env = ::testing::TempDir() + "deep_" + std::to_string(getpid()) + ".env";
  std::ofstream(env) << "'deep isovelocity 500 Hz'\n500\n1\n'CVW'\n0 0.0 1000\n0 1500 /\n1000 1500 /\n"
                     << "'A' 0.0\n1000 1600 0 1.5 0.5 0 /\n1\n30 /\n1\n50 /\n1\n1 /\n'I'\n0\n-80 80 /\n0 1001 3.5\n";
  const auto result = acomms::testing::run(ACOMMSCTL_BINARY, {"sim", "depth-adaptation", "--env", env, "--laps", "2"},
                                           log_prefix("deep"));
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("101 depths"), std::string::npos) << result.out;  // every 10 m
  EXPECT_NE(result.out.find("adaptation "), std::string::npos) << result.out;
  std::filesystem::remove(env);
}

TEST(DepthAdaptationCli, BadOptionsAreNamedByTheirFlags) {
  auto error_of = [](const std::vector<std::string>& extra, const std::string& name) {
    std::vector<std::string> args = {"sim", "depth-adaptation", "--env", kGlint10};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto result = acomms::testing::run(ACOMMSCTL_BINARY, args, log_prefix(name));
    EXPECT_NE(result.exit_code, 0) << name;
    return result.err;
  };
  EXPECT_NE(error_of({"--depths", "10,200"}, "depths").find("--depths = 200 must lie in the water column (0, 110) m"),
            std::string::npos);
  EXPECT_NE(error_of({"--sea-state", "9"}, "sea_state").find("--sea-state must be in 0..6, got 9"), std::string::npos);
  EXPECT_NE(error_of({"--min-depth", "-1"}, "min_depth").find("--min-depth"), std::string::npos);
  EXPECT_NE(error_of({"--excess-loss", "inf"}, "excess").find("--excess-loss = inf must be a finite number"),
            std::string::npos);
  EXPECT_NE(error_of({"--sweep", "depth", "1:2:1"}, "sweep_what").find("cannot sweep \"depth\" (known: noise, excess-loss)"),
            std::string::npos);
  EXPECT_NE(error_of({"--sweep", "noise", "110:100:2"}, "sweep_range").find("TO must be at least FROM"), std::string::npos);
}

// "Which case am I in?" on the shipped example: the sweep of the noise from
// the model's own level (every packet decodes: adapting cannot matter) to
// past the edge of reception. Each point is the replay at that level: at
// 106 dB the same figures as the single run above.
TEST(DepthAdaptationCli, TheSweepOnTheGlint10ExampleShowsWhereTheMarginRunsOut) {
  const std::string png = ::testing::TempDir() + "glint10_sweep_" + std::to_string(getpid()) + ".png";
  const auto result = acomms::testing::run(
      ACOMMSCTL_BINARY,
      {"--json", "sim", "depth-adaptation", "--env", kGlint10, "--sweep", "noise", "70:114:4", "--png", png},
      log_prefix("sweep"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  google::protobuf::Struct json;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(result.out, &json).ok()) << result.out;
  EXPECT_EQ(json.fields().at("quantity").string_value(), "noise_db");
  const auto& points = json.fields().at("points").list_value().values();
  ASSERT_EQ(points.size(), 12);
  double last_adaptive = 1, last_fixed = 1;
  for (int i = 0; i < points.size(); ++i) {
    const auto& p = points[i].struct_value().fields();
    EXPECT_EQ(p.at("value").number_value(), 70 + 4 * i);
    const double adaptive = p.at("adaptive").number_value(), fixed = p.at("fixed").number_value();
    EXPECT_LE(adaptive, last_adaptive) << i;
    EXPECT_LE(fixed, last_fixed) << i;
    last_adaptive = adaptive;
    last_fixed = fixed;
    if (p.at("value").number_value() <= 90) {
      EXPECT_EQ(adaptive, 1.0) << i;  // all the margin in the world
      EXPECT_EQ(p.at("margin_se").number_value(), 0.0) << i;
    }
    if (p.at("value").number_value() == 106) {
      EXPECT_NEAR(adaptive, 0.904, 0.002);
      EXPECT_EQ(p.at("best_fixed").string_value(), "90 m");
      EXPECT_NEAR(fixed, 0.900, 0.002);
    }
  }
  EXPECT_LT(last_adaptive, 0.8) << "the sweep must reach past the edge of reception";
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
  std::filesystem::remove(png);
}

}  // namespace
