// Keeping both ends in step: state saved and restored mid-stream, resent
// duplicates, lost deltas, configs that differ, malformed input.

#include <gtest/gtest.h>

#include "dccl/error.h"
#include "eval/track_generator.h"
#include "telemetry/telemetry_decoder.h"
#include "telemetry/telemetry_encoder.h"

namespace acomms::telemetry {
namespace {

std::vector<Sample> samples() {
  return sample_track(eval::generate_track(eval::TrackKind::kAuv, 11, 1800), 10);
}

TEST(StreamState, ARestoredEncoderSendsTheSameBytesAsTheOneThatKeptRunning) {
  const std::vector<Sample> track = samples();
  for (ObserverKind observer : {ObserverKind::kFixedSpeed, ObserverKind::kKalman}) {
    TelemetryConfig config;
    config.observer = observer;
    TelemetryEncoder running(config);
    for (size_t i = 0; i < 25; ++i) running.encode(track[i]);
    TelemetryEncoder restarted(config);
    ASSERT_TRUE(restarted.restore(running.state()));
    for (size_t i = 25; i < track.size(); ++i) {
      const EncodedMessage a = running.encode(track[i]);
      const EncodedMessage b = restarted.encode(track[i]);
      ASSERT_EQ(a.bytes, b.bytes) << i;
      ASSERT_EQ(a.bits, b.bits) << i;
    }
  }
}

TEST(StreamState, ARestoredDecoderDecodesTheRestOfTheStream) {
  const std::vector<Sample> track = samples();
  TelemetryConfig config;
  TelemetryEncoder encoder(config);
  TelemetryDecoder decoder(config);
  for (size_t i = 0; i < 30; ++i) decoder.decode(encoder.encode(track[i]).bytes);
  TelemetryDecoder restarted(config);
  ASSERT_TRUE(restarted.restore(decoder.state()));
  for (size_t i = 30; i < track.size(); ++i) {
    const EncodedMessage message = encoder.encode(track[i]);
    const DecodedMessage decoded = restarted.decode(message.bytes);
    ASSERT_EQ(decoded.outcome, DecodeOutcome::kPosition) << i;
    ASSERT_EQ(decoded.grid, message.position) << i;
  }
}

TEST(StreamState, StateFromAnotherConfigOrMalformedIsRefusedAndTheNextMessageIsAFull) {
  const std::vector<Sample> track = samples();
  TelemetryConfig config;
  TelemetryEncoder encoder(config);
  for (size_t i = 0; i < 5; ++i) encoder.encode(track[i]);
  const std::string state = encoder.state();
  TelemetryConfig other = config;
  other.tau_s = 20;
  TelemetryEncoder changed(other);
  EXPECT_FALSE(changed.restore(state));
  TelemetryEncoder same(config);
  EXPECT_FALSE(same.restore(state.substr(0, state.size() - 1)));
  EXPECT_EQ(same.encode(track[5]).kind, MessageKind::kFull);
  EXPECT_FALSE(same.restore(std::string("\x07garbage", 8)));
  EXPECT_TRUE(same.restore(state));
  EXPECT_EQ(same.encode(track[5]).kind, MessageKind::kDelta);
}

TEST(StreamState, AResentDuplicateIsIgnoredAndConsumesExactlyItsBits) {
  const std::vector<Sample> track = samples();
  TelemetryConfig config;
  TelemetryEncoder encoder(config);
  TelemetryDecoder decoder(config);
  decoder.decode(encoder.encode(track[0]).bytes);
  const EncodedMessage first = encoder.encode(track[1]);
  const EncodedMessage second = encoder.encode(track[2]);
  ASSERT_EQ(first.kind, MessageKind::kDelta);
  EXPECT_EQ(decoder.decode(first.bytes).outcome, DecodeOutcome::kPosition);
  // One frame: the resent first delta, then the second.
  std::string frame;
  dccl::BitWriter out(&frame);
  TelemetryEncoder replay(config);
  ASSERT_TRUE(replay.restore([&] {
    TelemetryEncoder e(config);
    e.encode(track[0]);
    return e.state();
  }()));
  replay.encode(track[1], out);
  replay.encode(track[2], out);
  dccl::BitReader in(frame);
  EXPECT_EQ(decoder.decode(in).outcome, DecodeOutcome::kDuplicate);
  EXPECT_EQ(in.position(), first.bits);
  const DecodedMessage decoded = decoder.decode(in);
  EXPECT_EQ(decoded.outcome, DecodeOutcome::kPosition);
  EXPECT_EQ(decoded.grid, second.position);
}

// The statistics outlive fulls, so a full that carries them on gives a
// decoder that missed a delta its position but not its step: it waits for
// the fresh full its receiver asks for (stream_receiver.h).
TEST(StreamState, AfterALostDeltaTheDecoderWaitsForAFreshFullAndIsInStepAgain) {
  const std::vector<Sample> track = samples();
  TelemetryConfig config;
  TelemetryEncoder encoder(config);
  TelemetryDecoder decoder(config);
  decoder.decode(encoder.encode(track[0]).bytes);
  encoder.encode(track[1]);  // lost
  EXPECT_EQ(decoder.decode(encoder.encode(track[2]).bytes).outcome, DecodeOutcome::kOutOfStep);
  EXPECT_EQ(decoder.decode(encoder.encode(track[3]).bytes).outcome, DecodeOutcome::kOutOfStep);
  encoder.request_full();  // the periodic full: carries the statistics on
  const EncodedMessage carried = encoder.encode(track[4]);
  ASSERT_EQ(carried.kind, MessageKind::kFull);
  EXPECT_FALSE(carried.fresh);
  const DecodedMessage position = decoder.decode(carried.bytes);
  EXPECT_EQ(position.outcome, DecodeOutcome::kPosition);
  EXPECT_EQ(position.grid, carried.position);
  EXPECT_FALSE(position.in_step);
  EXPECT_EQ(decoder.decode(encoder.encode(track[5]).bytes).outcome, DecodeOutcome::kOutOfStep);
  encoder.request_fresh();  // the receiver asked
  const EncodedMessage full = encoder.encode(track[6]);
  EXPECT_EQ(full.kind, MessageKind::kFull);
  EXPECT_TRUE(full.fresh);
  const DecodedMessage fresh = decoder.decode(full.bytes);
  EXPECT_EQ(fresh.grid, full.position);
  EXPECT_TRUE(fresh.in_step);
  const EncodedMessage delta = encoder.encode(track[7]);
  EXPECT_EQ(delta.kind, MessageKind::kDelta);
  EXPECT_EQ(decoder.decode(delta.bytes).grid, delta.position);
}

TEST(StreamState, AFullFromARestartedSenderResetsEvenWithTheLastSequenceNumber) {
  const std::vector<Sample> track = samples();
  TelemetryConfig config;
  TelemetryDecoder decoder(config);
  TelemetryEncoder before(config);
  // the sender's messages 1..16 (sequence 1..15, then 0) reach the receiver
  for (size_t i = 0; i < 16; ++i) decoder.decode(before.encode(track[i]).bytes);
  // it restarts without state and counts again: its full is sequence 1
  TelemetryEncoder after(config);
  for (size_t i = 0; i < 15; ++i) {
    after.request_full();
    after.encode(track[i]);
  }
  after.request_fresh();  // its statistics are not the ones the receiver holds
  const EncodedMessage full = after.encode(track[20]);
  ASSERT_EQ(full.kind, MessageKind::kFull);
  ASSERT_EQ(full.sequence, 0u);
  const DecodedMessage decoded = decoder.decode(full.bytes);
  EXPECT_EQ(decoded.outcome, DecodeOutcome::kPosition);
  EXPECT_EQ(decoded.grid, full.position);
  // resent right after itself, the same full is a duplicate
  EXPECT_EQ(decoder.decode(full.bytes).outcome, DecodeOutcome::kDuplicate);
  const EncodedMessage delta = after.encode(track[21]);
  ASSERT_EQ(delta.kind, MessageKind::kDelta);
  EXPECT_EQ(decoder.decode(delta.bytes).grid, delta.position);
}

TEST(StreamState, BadInputIsAnErrorNotACrash) {
  TelemetryConfig config;
  TelemetryDecoder decoder(config);
  EXPECT_THROW(decoder.decode(std::string()), dccl::TruncatedRead);
  // A full whose time of day is 2^17 - 1 (> 86399).
  std::string bytes;
  dccl::BitWriter out(&bytes);
  out.write(1, 1);
  out.write(0, 4);
  out.write((1u << 17) - 1, 17);
  out.write(0, 64);
  EXPECT_THROW(decoder.decode(bytes), dccl::Error);
  TelemetryEncoder encoder(config);
  Sample far;
  far.position_m = {1e6, 0, 0};
  EXPECT_THROW(encoder.encode(far), std::out_of_range);
  config.tau_s = 0;
  EXPECT_THROW(TelemetryEncoder{config}, std::invalid_argument);
}

}  // namespace
}  // namespace acomms::telemetry
