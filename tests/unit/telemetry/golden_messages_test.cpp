// Golden vectors: message sequences encoded once and checked in
// (golden/*.txt), decoded here to the checked-in positions. They pin the
// wire layout, the observers' arithmetic and the models' tables (with the
// statistics carried across the periodic fulls): a build (Debug or
// Release, another compiler or CPU) that predicts or tables one bit
// differently decodes a different position and fails here; and a state
// saved and reloaded mid-track (a SIGKILL of either end) gives the same
// bits as the run that went on.
//
// File format, one message per line: bits, hex bytes, then the expected
// time (s) and grid position x y z (precision steps) as the sender's sampler
// made them (not as a decoder reconstructed them). Regenerate only when the
// format changes on purpose:
//   telemetry_unit_tests --gtest_also_run_disabled_tests
//       --gtest_filter='*DISABLED_Regenerate*'

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "dccl/hex.h"
#include "eval/track_generator.h"
#include "telemetry/telemetry_decoder.h"
#include "telemetry/telemetry_encoder.h"

namespace acomms::telemetry {
namespace {

struct Vector {
  const char* file;
  ObserverKind observer;
  ModelKind model;
};

constexpr Vector kVectors[] = {
    {"kalman_learned.txt", ObserverKind::kKalman, ModelKind::kLearned},
    {"kalman_gaussian.txt", ObserverKind::kKalman, ModelKind::kGaussian},
    {"fixed_speed_adaptive.txt", ObserverKind::kFixedSpeed, ModelKind::kAdaptive},
};

TelemetryConfig config_of(const Vector& v) {
  TelemetryConfig config;
  config.observer = v.observer;
  config.model = v.model;
  config.full_every = 40;
  return config;
}

std::string path_of(const Vector& v) { return std::string(TELEMETRY_GOLDEN_DIR) + "/" + v.file; }

TEST(GoldenMessages, DecodeToTheCheckedInPositions) {
  for (const Vector& v : kVectors) {
    std::ifstream in(path_of(v));
    ASSERT_TRUE(in) << path_of(v);
    TelemetryDecoder decoder(config_of(v));
    std::string line;
    int lines = 0, deltas = 0;
    while (std::getline(in, line)) {
      std::istringstream fields(line);
      uint64_t bits;
      std::string hex;
      int64_t time;
      GridPosition want;
      ASSERT_TRUE(fields >> bits >> hex >> time >> want[0] >> want[1] >> want[2]) << v.file << ": " << line;
      const std::string bytes = dccl::from_hex(hex);
      dccl::BitReader reader(bytes);
      const DecodedMessage decoded = decoder.decode(reader);
      ASSERT_EQ(decoded.outcome, DecodeOutcome::kPosition) << v.file << " line " << lines + 1;
      EXPECT_EQ(reader.position(), bits) << v.file << " line " << lines + 1;
      EXPECT_EQ(decoded.grid, want) << v.file << " line " << lines + 1;
      EXPECT_EQ(unwrap_time_of_day(decoded.time_s, time), time) << v.file << " line " << lines + 1;
      deltas += decoded.kind == MessageKind::kDelta;
      ++lines;
    }
    EXPECT_GE(lines, 100) << v.file;
    EXPECT_GE(deltas, 90) << v.file;
  }
}

std::vector<Sample> golden_samples() {
  return sample_track(eval::generate_track(eval::TrackKind::kAuv, 5, 1500), 10);
}

struct GoldenLine {
  uint64_t bits = 0;
  std::string hex;
  GridPosition position{};
};

std::vector<GoldenLine> read_golden(const Vector& v) {
  std::ifstream in(path_of(v));
  std::vector<GoldenLine> lines;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    GoldenLine g;
    int64_t time;
    fields >> g.bits >> g.hex >> time >> g.position[0] >> g.position[1] >> g.position[2];
    lines.push_back(g);
  }
  return lines;
}

// A SIGKILL of either end: the state saved after message `cut` and loaded
// into a new encoder (decoder) gives the checked-in bits (positions) for
// the rest of the track. The cuts fall before, on and after the periodic
// fulls (every 41st message), so the statistics learned before a full must
// come back with the state for the bits after it to match.
TEST(GoldenMessages, AStateSavedAndReloadedMidTrackGivesTheSameBitsAsAnUninterruptedRun) {
  const std::vector<Sample> samples = golden_samples();
  for (const Vector& v : kVectors) {
    const std::vector<GoldenLine> golden = read_golden(v);
    ASSERT_EQ(golden.size(), samples.size()) << v.file;
    for (size_t cut : {20u, 41u, 42u, 60u, 83u, 100u, 124u, 140u}) {
      TelemetryEncoder before(config_of(v));
      TelemetryDecoder receiver(config_of(v));
      for (size_t i = 0; i < cut; ++i) {
        const EncodedMessage message = before.encode(samples[i]);
        ASSERT_EQ(dccl::to_hex(message.bytes), golden[i].hex) << v.file << " line " << i + 1;
        receiver.decode(dccl::from_hex(golden[i].hex));
      }
      TelemetryEncoder sender(config_of(v));
      ASSERT_TRUE(sender.restore(before.state())) << v.file << " cut " << cut;
      TelemetryDecoder decoder(config_of(v));
      ASSERT_TRUE(decoder.restore(receiver.state())) << v.file << " cut " << cut;
      for (size_t i = cut; i < samples.size(); ++i) {
        const EncodedMessage message = sender.encode(samples[i]);
        ASSERT_EQ(message.bits, golden[i].bits) << v.file << " cut " << cut << " line " << i + 1;
        ASSERT_EQ(dccl::to_hex(message.bytes), golden[i].hex) << v.file << " cut " << cut << " line " << i + 1;
        const DecodedMessage decoded = decoder.decode(dccl::from_hex(golden[i].hex));
        ASSERT_EQ(decoded.outcome, DecodeOutcome::kPosition) << v.file << " cut " << cut << " line " << i + 1;
        ASSERT_EQ(decoded.grid, golden[i].position) << v.file << " cut " << cut << " line " << i + 1;
      }
    }
  }
}

TEST(GoldenMessages, DISABLED_Regenerate) {
  const std::vector<Sample> samples = golden_samples();
  for (const Vector& v : kVectors) {
    TelemetryEncoder encoder(config_of(v));
    std::ofstream out(path_of(v));
    for (const Sample& sample : samples) {
      const EncodedMessage message = encoder.encode(sample);
      out << message.bits << ' ' << dccl::to_hex(message.bytes) << ' ' << sample.time_s;
      for (int axis = 0; axis < kAxes; ++axis) out << ' ' << std::llround(sample.position_m[axis]);
      out << '\n';
    }
  }
}

}  // namespace
}  // namespace acomms::telemetry
