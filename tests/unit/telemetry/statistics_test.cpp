// Statistics that outlive fulls (stream_predictor.h, telemetry_message.h):
// a periodic full costs only its own bits, a receiver that lost its state
// asks for and recovers in one fresh full, with fresh statistics on both
// ends, and never decodes a delta against statistics it does not hold.

#include <gtest/gtest.h>

#include <cmath>

#include "eval/track_generator.h"
#include "telemetry/sampler.h"
#include "telemetry/stream_receiver.h"
#include "telemetry/stream_sender.h"
#include "telemetry/telemetry_decoder.h"
#include "telemetry/telemetry_encoder.h"

namespace acomms::telemetry {
namespace {

constexpr double kEpoch = 1764000000;

std::vector<Sample> auv_samples(uint64_t seed, double duration_s) {
  std::vector<Fix> fixes = eval::generate_track(eval::TrackKind::kAuv, seed, duration_s);
  for (Fix& fix : fixes) fix.time_s += kEpoch;
  return sample_track(fixes, 10);
}

// The fresh bit of a full's body: after the time of day and x, y, z.
bool fresh_bit(const WireMessage& full, const TelemetryConfig& config) {
  const RegionGrid region = region_grid(config);
  return full.body.at(kTimeOfDayBits + region.bits[0] + region.bits[1] + region.bits[2]);
}

void expect_position(const ReceivedPosition& got, const Sample& sample, size_t i) {
  EXPECT_EQ(got.time_s, sample.time_s) << i;
  for (int axis = 0; axis < kAxes; ++axis)
    EXPECT_EQ(got.position_m[axis], std::round(sample.position_m[axis])) << "sample " << i << " axis " << axis;
}

TEST(Statistics, DeltasAfterAPeriodicFullCostExactlyWhatTheyCostWithoutIt) {
  const std::vector<Sample> samples = auv_samples(7, 3 * 3600);
  for (ObserverKind observer : {ObserverKind::kFixedSpeed, ObserverKind::kKalman}) {
    for (ModelKind model : {ModelKind::kUniform, ModelKind::kGaussian, ModelKind::kAdaptive, ModelKind::kLearned}) {
      TelemetryConfig without;
      without.observer = observer;
      without.model = model;
      without.full_every = 10000;
      TelemetryConfig with = without;
      with.full_every = 60;
      TelemetryEncoder a(without), b(with);
      TelemetryDecoder decoder(with);
      int periodic = 0, deltas_after_periodic = 0;
      for (size_t i = 0; i < samples.size(); ++i) {
        const EncodedMessage plain = a.encode(samples[i]);
        const EncodedMessage message = b.encode(samples[i]);
        const DecodedMessage decoded = decoder.decode(message.bytes);
        ASSERT_EQ(decoded.outcome, DecodeOutcome::kPosition) << i;
        ASSERT_TRUE(decoded.in_step) << i;
        ASSERT_EQ(decoded.grid, message.position) << i;
        if (plain.kind == MessageKind::kDelta && message.kind == MessageKind::kFull) {
          ++periodic;
          EXPECT_FALSE(message.fresh) << i;
          continue;
        }
        ASSERT_EQ(plain.kind, message.kind) << i;
        if (message.kind == MessageKind::kFull) continue;
        // Same header (kind, sequence), same codeword: the same bytes.
        ASSERT_EQ(plain.bytes, message.bytes) << name_of(observer) << " + " << name_of(model) << ", sample " << i;
        if (periodic > 0) ++deltas_after_periodic;
      }
      EXPECT_GE(periodic, 10) << name_of(observer) << " + " << name_of(model);
      EXPECT_GE(deltas_after_periodic, 600) << name_of(observer) << " + " << name_of(model);
    }
  }
}

TEST(Statistics, OnlyTheFirstFullIsFreshWhileBothEndsKeepTheirState) {
  const std::vector<Sample> samples = auv_samples(3, 2 * 3600);
  TelemetryConfig config;
  TelemetryEncoder encoder(config);
  int fulls = 0, fresh = 0;
  for (const Sample& sample : samples) {
    const EncodedMessage message = encoder.encode(sample);
    fulls += message.kind == MessageKind::kFull;
    fresh += message.fresh;
  }
  EXPECT_GE(fulls, 10);
  EXPECT_EQ(fresh, 1);
}

struct Link {
  TelemetryConfig config;
  std::vector<Sample> samples = auv_samples(9, 3 * 3600);
  StreamSender sender{config, 2, 1};
  size_t next = 0;

  WireMessage send() { return sender.send(samples[next++]); }
  double now() const { return static_cast<double>(samples[next - 1].time_s) + 5; }
};

// A receiver's store is wiped (or the node replaced) mid-stream: its first
// message is a delta, it asks, and the sender's next message is a fresh
// full from which everything decodes; the sender's deltas after it are
// byte for byte those of a sender that starts afresh there.
TEST(Statistics, AReceiverThatLostItsStateRecoversInOneFreshFullOnBothEnds) {
  Link link;
  StreamReceiver receiver(link.config, 2, 1800);
  for (int i = 0; i < 150; ++i) {
    ASSERT_EQ(receiver.receive(link.send(), link.now()).size(), 1u) << i;
    ASSERT_FALSE(receiver.take_feedback()) << i;
  }
  StreamReceiver wiped(link.config, 2, 1800);
  WireMessage delta = link.send();
  while (delta.kind != MessageKind::kDelta) delta = link.send();
  EXPECT_TRUE(wiped.receive(delta, link.now()).empty());
  const std::optional<Feedback> ask = wiped.take_feedback();
  ASSERT_TRUE(ask);
  EXPECT_FALSE(ask->heard) << "a receiver without state heard nothing";
  EXPECT_FALSE(wiped.take_feedback()) << "asked once";
  ASSERT_TRUE(link.sender.on_feedback(ask->heard));

  const size_t fresh_at = link.next;
  const WireMessage full = link.send();
  ASSERT_EQ(full.kind, MessageKind::kFull);
  EXPECT_TRUE(fresh_bit(full, link.config));
  std::vector<ReceivedPosition> got = wiped.receive(full, link.now());
  ASSERT_EQ(got.size(), 1u);
  expect_position(got[0], link.samples[fresh_at], fresh_at);

  StreamSender newcomer(link.config, 2, 1);
  EXPECT_EQ(newcomer.send(link.samples[fresh_at]).body, full.body);
  while (link.next < link.samples.size()) {
    const size_t i = link.next;
    const WireMessage message = link.send();
    const WireMessage fresh = newcomer.send(link.samples[i]);
    ASSERT_EQ(message.kind, fresh.kind) << i;
    ASSERT_EQ(message.body, fresh.body) << i;
    got = wiped.receive(message, link.now());
    ASSERT_EQ(got.size(), 1u) << i;
    expect_position(got[0], link.samples[i], i);
    ASSERT_FALSE(wiped.take_feedback()) << i;
  }
  EXPECT_EQ(wiped.counters().out_of_step, 0u);
}

// A receiver whose first message after losing its state is a full that
// carries the statistics on: the full's position is good, the deltas after
// it are not decoded (out of step), and it asks once, having heard the full.
TEST(Statistics, AFullWhoseStatisticsTheReceiverDoesNotHoldDeliversItsPositionButNoDelta) {
  Link link;
  StreamReceiver receiver(link.config, 2, 1800);
  WireMessage message = link.send();
  while (link.next < 100 || message.kind != MessageKind::kFull) message = link.send();
  EXPECT_FALSE(fresh_bit(message, link.config));
  std::vector<ReceivedPosition> got = receiver.receive(message, link.now());
  ASSERT_EQ(got.size(), 1u);
  expect_position(got[0], link.samples[link.next - 1], link.next - 1);
  const std::optional<Feedback> ask = receiver.take_feedback();
  ASSERT_TRUE(ask);
  EXPECT_EQ(ask->heard, message.sequence);
  for (int i = 0; i < 5; ++i) {
    EXPECT_TRUE(receiver.receive(link.send(), link.now()).empty());
    EXPECT_FALSE(receiver.take_feedback());
  }
  EXPECT_EQ(receiver.counters().out_of_step, 5u);
  ASSERT_TRUE(link.sender.on_feedback(ask->heard));
  const WireMessage full = link.send();
  ASSERT_EQ(full.kind, MessageKind::kFull);
  EXPECT_TRUE(fresh_bit(full, link.config));
  EXPECT_EQ(receiver.receive(full, link.now()).size(), 1u);
  for (int i = 0; i < 20; ++i) {
    got = receiver.receive(link.send(), link.now());
    ASSERT_EQ(got.size(), 1u) << i;
    expect_position(got[0], link.samples[link.next - 1], link.next - 1);
  }
}

// The sender gave up on a delta (its ttl passed): the receiver consumes the
// next full past the gap, knows its statistics miss what was lost, asks,
// and is in step again from the sender's next (fresh) full.
TEST(Statistics, AReceiverThatSkippedAGapAsksAndRecovers) {
  Link link;
  StreamReceiver receiver(link.config, 2, 600);
  while (link.next < 70) ASSERT_EQ(receiver.receive(link.send(), link.now()).size(), 1u);
  WireMessage lost = link.send();
  ASSERT_EQ(lost.kind, MessageKind::kDelta);
  WireMessage message = link.send();
  while (message.kind != MessageKind::kFull) {
    EXPECT_TRUE(receiver.receive(message, link.now()).empty());
    message = link.send();
  }
  // Held; the next message comes after the gap timeout: the full is
  // consumed without the lost delta, the delta after it cannot be.
  EXPECT_TRUE(receiver.receive(message, link.now()).empty());
  const WireMessage after = link.send();
  ASSERT_EQ(after.kind, MessageKind::kDelta);
  const std::vector<ReceivedPosition> at_timeout = receiver.receive(after, link.now() + 700);
  ASSERT_EQ(at_timeout.size(), 1u) << "the full's position, not the delta's";
  expect_position(at_timeout[0], link.samples[link.next - 2], link.next - 2);
  EXPECT_EQ(receiver.counters().gaps_skipped, 1u);
  EXPECT_EQ(receiver.counters().out_of_step, 1u);
  const std::optional<Feedback> ask = receiver.take_feedback();
  ASSERT_TRUE(ask);
  EXPECT_EQ(ask->heard, after.sequence);
  ASSERT_TRUE(link.sender.on_feedback(ask->heard));
  const WireMessage full = link.send();
  EXPECT_TRUE(fresh_bit(full, link.config));
  EXPECT_EQ(receiver.receive(full, link.now() + 700).size(), 1u);
  for (int i = 0; i < 30; ++i) {
    const std::vector<ReceivedPosition> got = receiver.receive(link.send(), link.now() + 700);
    ASSERT_EQ(got.size(), 1u) << i;
    expect_position(got[0], link.samples[link.next - 1], link.next - 1);
  }
}

// A request that crossed the fresh full answering an earlier one (the
// receiver had not consumed it yet) does not cost another fresh start.
TEST(Statistics, ARequestOlderThanTheLastFreshFullIsIgnored) {
  Link link;
  for (int i = 0; i < 10; ++i) link.send();
  const uint32_t heard = link.sender.last_sequence();
  ASSERT_TRUE(link.sender.on_feedback(std::nullopt));
  const WireMessage fresh = link.send();
  ASSERT_TRUE(fresh_bit(fresh, link.config));
  EXPECT_FALSE(link.sender.on_feedback(heard));
  EXPECT_EQ(link.send().kind, MessageKind::kDelta);
  EXPECT_TRUE(link.sender.on_feedback(fresh.sequence)) << "lost again after the fresh full";
  const WireMessage again = link.send();
  EXPECT_EQ(again.kind, MessageKind::kFull);
  EXPECT_TRUE(fresh_bit(again, link.config));
}

// A sender restarted from its state keeps its statistics: the restart's
// full re-anchors (a new segment) and carries them on, and the receiver
// that kept its own decodes on without asking.
TEST(Statistics, ASenderRestartedFromItsStateKeepsTheStatistics) {
  Link link;
  StreamReceiver receiver(link.config, 2, 1800);
  while (link.next < 200) ASSERT_EQ(receiver.receive(link.send(), link.now()).size(), 1u);
  StreamSender restarted(link.config, 2, 1);
  ASSERT_TRUE(restarted.restore(link.sender.state()));
  Sample first = link.samples[link.next];
  first.new_segment = true;
  const WireMessage full = restarted.send(first);
  ++link.next;
  ASSERT_EQ(full.kind, MessageKind::kFull);
  EXPECT_FALSE(fresh_bit(full, link.config));
  EXPECT_EQ(receiver.receive(full, link.now()).size(), 1u);
  EXPECT_FALSE(receiver.take_feedback());
  for (int i = 0; i < 50; ++i) {
    const std::vector<ReceivedPosition> got = receiver.receive(restarted.send(link.samples[link.next++]), link.now());
    ASSERT_EQ(got.size(), 1u) << i;
    expect_position(got[0], link.samples[link.next - 1], link.next - 1);
  }
}

}  // namespace
}  // namespace acomms::telemetry
