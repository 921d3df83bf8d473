// The telemetry evaluation as a library: loss with resends against the
// newest-full scheme (Schneider 2013 section 3.7), and the track reader.

#include "eval/telemetry_evaluation.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "eval/track_generator.h"

namespace acomms::eval {
namespace {

std::vector<telemetry::Sample> samples() {
  return telemetry::sample_track(generate_track(TrackKind::kAuv, 2, 3600), 10);
}

TEST(TelemetryEvaluation, ResendingDeltasCostsLessThanNewestFullsAndLatencyGrowsWithLoss) {
  telemetry::TelemetryConfig config;
  config.observer = telemetry::ObserverKind::kFixedSpeed;
  const TelemetryRun lossless = evaluate_telemetry(samples(), config, TelemetryLossConfig{});
  EXPECT_FALSE(lossless.with_loss);
  EXPECT_EQ(lossless.deltas + lossless.fulls, lossless.positions);
  double last_latency = 0;
  for (double p : {0.1, 0.4, 0.7}) {
    const TelemetryRun run = evaluate_telemetry(samples(), config, TelemetryLossConfig{p, 256, 3});
    ASSERT_TRUE(run.with_loss);
    EXPECT_LT(run.loss_delta_bits_per_position, run.loss_newest_bits_per_position) << p;
    EXPECT_GT(run.loss_delta_bits_per_position, lossless.message_bits_mean) << p;
    EXPECT_GT(run.loss_extra_latency_s, last_latency) << p;
    last_latency = run.loss_extra_latency_s;
  }
}

TEST(TelemetryEvaluation, TrackReaderNamesTheFileAndLine) {
  const std::string path = ::testing::TempDir() + "track_" + std::to_string(getpid()) + ".csv";
  auto write = [&](const std::string& text) {
    std::ofstream(path) << text;
  };
  write("t,x,y,z\n0,1,2,-3\n\n5,1.5,2,-3.5\r\n");
  const std::vector<telemetry::Fix> fixes = read_track_csv(path);
  ASSERT_EQ(fixes.size(), 2u);
  EXPECT_DOUBLE_EQ(fixes[1].position_m[2], -3.5);
  write("time,x,y,z\n");
  EXPECT_THROW(read_track_csv(path), std::runtime_error);
  write("t,x,y,z\n0,1,2\n");
  try {
    read_track_csv(path);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":2:"), std::string::npos) << e.what();
  }
  write("t,x,y,z\n5,1,2,3\n5,1,2,3\n");
  EXPECT_THROW(read_track_csv(path), std::runtime_error);
  EXPECT_THROW(read_track_csv(path + ".missing"), std::runtime_error);
}

}  // namespace
}  // namespace acomms::eval
