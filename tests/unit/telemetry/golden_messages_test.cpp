// Golden vectors: message sequences encoded once and checked in
// (golden/*.txt), decoded here to the checked-in positions. They pin the
// wire layout, the observers' arithmetic and the models' tables: a build
// (Debug or Release, another compiler or CPU) that predicts or tables one
// bit differently decodes a different position and fails here.
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

TEST(GoldenMessages, DISABLED_Regenerate) {
  const std::vector<Sample> samples = sample_track(eval::generate_track(eval::TrackKind::kAuv, 5, 1500), 10);
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
