// The telemetry stream as the link carries it (stream_sender.h,
// stream_receiver.h, wire_message.h): in order or not, with resends, with
// either end restarted from its stored state or without it, the receiver
// reconstructs every sample exactly, once, in order, and never decodes a
// delta against the wrong state.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "dccl/codec.h"
#include "eval/realistic_track.h"
#include "eval/track_generator.h"
#include "telemetry/sampler.h"
#include "telemetry/stream_receiver.h"
#include "telemetry/stream_sender.h"

namespace acomms::telemetry {
namespace {

constexpr double kEpoch = 1764000000;  // 2025-11-24 16:00 UTC: sample times are UTC

std::vector<Sample> track_samples(eval::TrackKind kind, uint64_t seed, double duration_s, uint32_t tau_s) {
  std::vector<Fix> fixes = eval::generate_track(kind, seed, duration_s);
  for (Fix& fix : fixes) fix.time_s += kEpoch;
  return sample_track(fixes, tau_s);
}

struct Sent {
  WireMessage message;
  Sample sample;
};

std::vector<Sent> send_all(StreamSender& sender, const std::vector<Sample>& samples) {
  std::vector<Sent> out;
  for (const Sample& s : samples) out.push_back({sender.send(s), s});
  return out;
}

// What the receiver must end up with for `sent`: every sample, on the grid.
void expect_positions(const std::vector<ReceivedPosition>& got, const std::vector<Sent>& sent,
                      const TelemetryConfig& config) {
  ASSERT_EQ(got.size(), sent.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].time_s, sent[i].sample.time_s) << i;
    EXPECT_EQ(got[i].full, sent[i].message.kind == MessageKind::kFull) << i;
    for (int axis = 0; axis < kAxes; ++axis) {
      EXPECT_EQ(got[i].position_m[axis], std::round(sent[i].sample.position_m[axis] / config.precision_m) *
                                             config.precision_m)
          << "sample " << i << " axis " << axis;
    }
    if (::testing::Test::HasFailure()) return;
  }
}

void append(std::vector<ReceivedPosition>* all, std::vector<ReceivedPosition> more) {
  all->insert(all->end(), more.begin(), more.end());
}

TEST(StreamLinkTest, InOrderDeliveryReconstructsEverySampleExactly) {
  TelemetryConfig config;
  StreamSender sender(config, 2, 1);
  StreamReceiver receiver(config, 2, 1800);
  const std::vector<Sent> sent = send_all(sender, track_samples(eval::TrackKind::kAuv, 7, 4 * 3600, config.tau_s));
  std::vector<ReceivedPosition> got;
  for (const Sent& s : sent) append(&got, receiver.receive(s.message, static_cast<double>(s.sample.time_s) + 30));
  expect_positions(got, sent, config);
  EXPECT_EQ(receiver.counters().duplicates, 0u);
  EXPECT_EQ(receiver.held(), 0u);
}

// The realistic tracks (eval/realistic_track.h) through sender and receiver,
// every observer and model: every position reconstructed on the grid.
TEST(StreamLinkTest, RealisticTorpedoAuvAndGliderTracksReconstructEverySampleWithinThePrecision) {
  for (eval::TrackKind kind : {eval::TrackKind::kAuv, eval::TrackKind::kGlider}) {
    std::vector<Fix> fixes = eval::generate_realistic_track(kind, 12, 3 * 3600);
    for (Fix& fix : fixes) fix.time_s += kEpoch;
    for (ObserverKind observer : {ObserverKind::kFixedSpeed, ObserverKind::kKalman}) {
      for (ModelKind model : {ModelKind::kUniform, ModelKind::kGaussian, ModelKind::kAdaptive, ModelKind::kLearned}) {
        TelemetryConfig config;
        config.observer = observer;
        config.model = model;
        config.speed_mps = kind == eval::TrackKind::kAuv ? 1.5 : 0.3;
        StreamSender sender(config, 2, 1);
        StreamReceiver receiver(config, 2, 1800);
        const std::vector<Sent> sent = send_all(sender, sample_track(fixes, config.tau_s));
        ASSERT_GT(sent.size(), 1000u);
        std::vector<ReceivedPosition> got;
        for (const Sent& s : sent) append(&got, receiver.receive(s.message, static_cast<double>(s.sample.time_s) + 30));
        expect_positions(got, sent, config);
        ASSERT_FALSE(HasFailure()) << name_of(observer) << " + " << name_of(model);
        EXPECT_EQ(receiver.counters().duplicates, 0u);
      }
    }
  }
}

// Resends (an ACK lost) and reordering (a lost frame resent after later
// ones), as a lossy link with acks delivers them.
TEST(StreamLinkTest, ReorderedAndRepeatedMessagesAreAppliedOnceInOrder) {
  for (ObserverKind observer : {ObserverKind::kFixedSpeed, ObserverKind::kKalman}) {
    TelemetryConfig config;
    config.observer = observer;
    StreamSender sender(config, 2, 1);
    StreamReceiver receiver(config, 2, 1800);
    const std::vector<Sent> sent = send_all(sender, track_samples(eval::TrackKind::kAuv, 3, 3 * 3600, config.tau_s));
    std::mt19937_64 rng(11);
    std::vector<size_t> order;
    for (size_t i = 0; i < sent.size(); ++i) {
      order.push_back(i);
      if (rng() % 4 == 0) order.push_back(i);  // a resend
    }
    // Each message may arrive up to 8 places late.
    for (size_t i = 0; i + 1 < order.size(); ++i) {
      size_t j = std::min(order.size() - 1, i + rng() % 8);
      std::swap(order[i], order[j]);
    }
    std::vector<ReceivedPosition> got;
    for (size_t i : order) append(&got, receiver.receive(sent[i].message, static_cast<double>(sent[i].sample.time_s)));
    expect_positions(got, sent, config);
    EXPECT_GT(receiver.counters().duplicates, 0u);
    EXPECT_EQ(receiver.counters().out_of_step, 0u);
  }
}

TEST(StreamLinkTest, SequenceNumbersWrapWithoutLoss) {
  TelemetryConfig config;
  StreamSender sender(config, 2, 1);
  StreamReceiver receiver(config, 2, 1800);
  // More than 4096 messages: the 12-bit sequence wraps.
  const std::vector<Sent> sent = send_all(sender, track_samples(eval::TrackKind::kAuv, 5, 50000, config.tau_s));
  ASSERT_GT(sent.size(), kWireSequenceModulus);
  std::vector<ReceivedPosition> got;
  for (const Sent& s : sent) append(&got, receiver.receive(s.message, static_cast<double>(s.sample.time_s)));
  expect_positions(got, sent, config);
}

TEST(StreamLinkTest, SenderRestartedFromItsStateCostsOneFull) {
  TelemetryConfig config;
  const std::vector<Sample> samples = track_samples(eval::TrackKind::kAuv, 9, 2 * 3600, config.tau_s);
  const size_t half = 300;
  StreamSender before(config, 2, 1);
  StreamReceiver receiver(config, 2, 1800);
  std::vector<Sent> sent = send_all(before, {samples.begin(), samples.begin() + half});
  StreamSender after(config, 2, 1);
  ASSERT_TRUE(after.restore(before.state()));
  // The restarted daemon's sampler starts a new segment.
  std::vector<Sample> rest(samples.begin() + half, samples.end());
  rest.front().new_segment = true;
  std::vector<Sent> more = send_all(after, rest);
  EXPECT_EQ(more.front().message.kind, MessageKind::kFull);
  EXPECT_EQ(more.front().message.sequence, (before.last_sequence() + 1) % kWireSequenceModulus);
  sent.insert(sent.end(), more.begin(), more.end());
  std::vector<ReceivedPosition> got;
  for (const Sent& s : sent) append(&got, receiver.receive(s.message, static_cast<double>(s.sample.time_s)));
  expect_positions(got, sent, config);
}

// Killed after a message was stored but before its stream state was: the
// restarted sender continues after the newest queued sequence, so the
// receiver gets no number twice and waits for none that does not exist.
TEST(StreamLinkTest, SenderStateBehindTheQueueContinuesAfterTheNewestQueued) {
  TelemetryConfig config;
  const std::vector<Sample> samples = track_samples(eval::TrackKind::kAuv, 12, 3600, config.tau_s);
  StreamSender before(config, 2, 1);
  StreamReceiver receiver(config, 2, 1800);
  std::vector<Sent> sent = send_all(before, {samples.begin(), samples.begin() + 100});
  const std::string stored = before.state();  // then one more message was queued, its state lost
  sent.push_back({before.send(samples[100]), samples[100]});
  StreamSender after(config, 2, 1);
  ASSERT_TRUE(after.restore(stored));
  after.continue_after(sent.back().message.sequence);
  after.continue_after(sent[50].message.sequence);  // older queued ones change nothing
  std::vector<Sample> rest(samples.begin() + 101, samples.end());
  rest.front().new_segment = true;
  std::vector<Sent> more = send_all(after, rest);
  EXPECT_EQ(more.front().message.sequence, (sent.back().message.sequence + 1) % kWireSequenceModulus);
  EXPECT_EQ(more.front().message.kind, MessageKind::kFull);
  sent.insert(sent.end(), more.begin(), more.end());
  std::vector<ReceivedPosition> got;
  for (const Sent& s : sent) append(&got, receiver.receive(s.message, static_cast<double>(s.sample.time_s)));
  expect_positions(got, sent, config);
  EXPECT_EQ(receiver.held(), 0u);
}

TEST(StreamLinkTest, SenderThatLostItsStateIsFollowedFromItsNextFull) {
  TelemetryConfig config;
  const std::vector<Sample> samples = track_samples(eval::TrackKind::kGlider, 2, 8 * 3600, config.tau_s);
  StreamSender before(config, 2, 1);
  StreamReceiver receiver(config, 2, 1800);
  std::vector<Sent> sent = send_all(before, {samples.begin(), samples.begin() + 1000});
  StreamSender wiped(config, 2, 1);  // store wiped: counts from 0 again
  EXPECT_FALSE(wiped.restore(""));
  std::vector<Sent> more = send_all(wiped, {samples.begin() + 1000, samples.end()});
  EXPECT_EQ(more.front().message.sequence, 0u);
  sent.insert(sent.end(), more.begin(), more.end());
  std::vector<ReceivedPosition> got;
  for (const Sent& s : sent) append(&got, receiver.receive(s.message, static_cast<double>(s.sample.time_s)));
  expect_positions(got, sent, config);
}

// The old count up to `last` (messages 0..last), then a sender that lost its
// state counts from 0 again over the next `restarted` samples, its first
// `silence_s` later than the old count's last (in the cycle's upper half
// for last > 2048, where 0 reads as 4096 - last ahead).
struct Restart {
  std::vector<Sent> before;
  std::vector<Sent> after;
};
Restart restart_after(const TelemetryConfig& config, uint64_t seed, uint32_t last, size_t restarted,
                      int64_t silence_s) {
  // Tracks have gaps (fewer samples than duration / tau): half as long again.
  const double duration_s = 1.5 * static_cast<double>(last + 1 + restarted) * config.tau_s;
  std::vector<Sample> samples = track_samples(eval::TrackKind::kAuv, seed, duration_s, config.tau_s);
  if (samples.size() < last + 1 + restarted) {
    ADD_FAILURE() << "the track has " << samples.size() << " samples";
    return {};
  }
  StreamSender before(config, 2, 1);
  Restart r;
  r.before = send_all(before, {samples.begin(), samples.begin() + last + 1});
  EXPECT_EQ(before.last_sequence(), last);
  StreamSender wiped(config, 2, 1);
  EXPECT_FALSE(wiped.restore(""));
  std::vector<Sample> rest(samples.begin() + last + 1, samples.begin() + last + 1 + static_cast<long>(restarted));
  const int64_t shift = r.before.back().sample.time_s + silence_s - rest.front().time_s;
  for (Sample& s : rest) s.time_s += shift;
  r.after = send_all(wiped, rest);
  EXPECT_EQ(r.after.front().message.sequence, 0u);
  EXPECT_EQ(r.after.front().message.kind, MessageKind::kFull);
  return r;
}

// The bug this guards: 0 after 3000 reads as 1096 messages ahead, so the
// restarted sender's full was held for gap_timeout_s (30 min of nothing).
// Its time, 10 s on where 1096 messages take 10960 s, shows a new count.
TEST(StreamLinkTest, SenderRestartedWithoutStateInTheUpperHalfOfTheCycleIsFollowedAtOnce) {
  TelemetryConfig config;
  const Restart r = restart_after(config, 21, 3000, 120, config.tau_s);
  ASSERT_FALSE(r.after.empty());
  StreamReceiver receiver(config, 2, 1800);
  std::vector<ReceivedPosition> got;
  for (const Sent& s : r.before) append(&got, receiver.receive(s.message, static_cast<double>(s.sample.time_s)));
  for (const Sent& s : r.after) {
    std::vector<ReceivedPosition> now = receiver.receive(s.message, static_cast<double>(s.sample.time_s));
    ASSERT_EQ(now.size(), 1u) << "message " << s.message.sequence << " of the new count, on its arrival";
    append(&got, now);
  }
  std::vector<Sent> all = r.before;
  all.insert(all.end(), r.after.begin(), r.after.end());
  expect_positions(got, all, config);
  EXPECT_EQ(receiver.held(), 0u);
  EXPECT_EQ(receiver.counters().fresh_starts, 1u);
}

// The restarted sender's full lost once and resent after its first deltas
// (which the receiver acked, so they never come again): they follow on from
// it. A full of the old count held past a gap is delivered first, as the gap
// timeout would have delivered it half an hour later; the old count's deltas
// after it are not decoded (coded against statistics that include the lost
// delta: statistics outlive fulls), and the new count's fresh full puts the
// receiver in step again.
TEST(StreamLinkTest, RestartFullDeliversTheOldCountsHeldFullsThenItsOwnDeltasThatCameFirst) {
  TelemetryConfig config;
  const Restart r = restart_after(config, 22, 3000, 30, 600);
  ASSERT_FALSE(r.after.empty());
  size_t old_full = r.before.size() - 2;
  while (r.before[old_full].message.kind != MessageKind::kFull) --old_full;
  const size_t lost = old_full - 2;  // never comes: its sender lost it
  ASSERT_EQ(r.before[lost].message.kind, MessageKind::kDelta);
  StreamReceiver receiver(config, 2, 1800);
  std::vector<ReceivedPosition> got;
  for (size_t i = 0; i < r.before.size(); ++i) {
    if (i != lost) append(&got, receiver.receive(r.before[i].message, static_cast<double>(r.before[i].sample.time_s)));
  }
  ASSERT_EQ(receiver.held(), r.before.size() - 1 - lost);
  const double now = static_cast<double>(r.after[5].sample.time_s);
  for (size_t i = 1; i <= 5; ++i) EXPECT_TRUE(receiver.receive(r.after[i].message, now).empty());
  // The full: the old count's held full, the full, its 5 deltas.
  std::vector<ReceivedPosition> at_once = receiver.receive(r.after[0].message, now);
  EXPECT_EQ(at_once.size(), 1u + 6);
  EXPECT_EQ(receiver.counters().out_of_step, r.before.size() - old_full - 1);
  append(&got, at_once);
  for (size_t i = 6; i < r.after.size(); ++i) {
    append(&got, receiver.receive(r.after[i].message, static_cast<double>(r.after[i].sample.time_s)));
  }
  std::vector<Sent> expected(r.before.begin(), r.before.begin() + static_cast<long>(lost));
  expected.push_back(r.before[old_full]);
  expected.insert(expected.end(), r.after.begin(), r.after.end());
  expect_positions(got, expected, config);
  EXPECT_EQ(receiver.held(), 0u);
  EXPECT_EQ(receiver.counters().fresh_starts, 1u);
  EXPECT_EQ(receiver.counters().gaps_skipped, 1u);
}

// Back after 6 h without its state (2160 tau: more than half a cycle, the
// longest ttl_s): 0 after 4000 reads as 96 ahead, which 6 h of samples
// could be, but past half a cycle the number cannot tell.
TEST(StreamLinkTest, SenderBackWithoutStateAfterHalfACycleOfSilenceIsFollowedAtOnce) {
  TelemetryConfig config;
  const Restart r = restart_after(config, 23, 4000, 20, 6 * 3600);
  ASSERT_FALSE(r.after.empty());
  StreamReceiver receiver(config, 2, 1800);
  std::vector<ReceivedPosition> got;
  for (const Sent& s : r.before) append(&got, receiver.receive(s.message, static_cast<double>(s.sample.time_s)));
  ASSERT_EQ(receiver.receive(r.after.front().message, static_cast<double>(r.after.front().sample.time_s)).size(), 1u);
  EXPECT_EQ(receiver.counters().fresh_starts, 1u);
  EXPECT_EQ(receiver.held(), 0u);
}

// Not a restart: one sender, its navigation out for 6 h (2160 tau, past
// half a cycle), the last 5 messages before it lost for good, and the first
// full after it lost once and resent after its first 3 deltas. Its own
// deltas, heard after it was sampled, follow on from it (consumed in order,
// none held) but are not decoded: the sender's statistics include the 5
// lost messages. The receiver asks; the sender's next message is a fresh
// full, and every position from it on arrives.
TEST(StreamLinkTest, AfterHalfACycleOfSilenceDeltasThatOvertookTheirFullFollowItAndAFreshFullResumes) {
  TelemetryConfig config;
  const std::vector<Sample> samples = track_samples(eval::TrackKind::kAuv, 31, 3 * 3600, config.tau_s);
  ASSERT_GT(samples.size(), 140u);
  std::vector<Sample> before(samples.begin(), samples.begin() + 100);
  std::vector<Sample> after(samples.begin() + 100, samples.begin() + 104);
  std::vector<Sample> resumed(samples.begin() + 104, samples.begin() + 140);
  for (Sample& sample : after) sample.time_s += 6 * 3600;
  for (Sample& sample : resumed) sample.time_s += 6 * 3600;
  after.front().new_segment = true;
  StreamSender sender(config, 2, 1);
  const std::vector<Sent> a = send_all(sender, before);
  const std::vector<Sent> b = send_all(sender, after);
  ASSERT_EQ(b.front().message.kind, MessageKind::kFull);
  ASSERT_EQ(b[1].message.kind, MessageKind::kDelta);
  StreamReceiver receiver(config, 2, 1800);
  for (size_t i = 0; i + 5 < a.size(); ++i) receiver.receive(a[i].message, static_cast<double>(a[i].sample.time_s));
  const double now = static_cast<double>(b[3].sample.time_s);
  for (size_t i = 1; i <= 3; ++i) EXPECT_TRUE(receiver.receive(b[i].message, now).empty());
  std::vector<ReceivedPosition> got = receiver.receive(b[0].message, now);
  ASSERT_EQ(got.size(), 1u) << "the full; the 3 deltas that came before it are consumed, not decoded";
  expect_positions(got, {b[0]}, config);
  EXPECT_EQ(receiver.held(), 0u);
  EXPECT_EQ(receiver.counters().out_of_step, 3u);
  const std::optional<Feedback> ask = receiver.take_feedback();
  ASSERT_TRUE(ask);
  EXPECT_EQ(ask->heard, b[3].message.sequence);
  ASSERT_TRUE(sender.on_feedback(ask->heard));
  const std::vector<Sent> c = send_all(sender, resumed);
  ASSERT_EQ(c.front().message.kind, MessageKind::kFull);
  got.clear();
  for (const Sent& s : c) append(&got, receiver.receive(s.message, static_cast<double>(s.sample.time_s)));
  expect_positions(got, c, config);
  EXPECT_EQ(receiver.held(), 0u);
  EXPECT_EQ(receiver.counters().out_of_step, 3u);
}

// The reverse risk: a full of the old count resent late (its ACK was lost)
// after the receiver followed a restart. Its number reads as ahead of the
// new count, its time as old: not a restart, and not held either (after
// the gap timeout it would be consumed as the next full and the stream
// would jump back an hour and then drop the new count as resends).
TEST(StreamLinkTest, LateOldFullAfterARestartNeitherRestartsNorWaitsToBeConsumed) {
  TelemetryConfig config;
  const Restart r = restart_after(config, 24, 1499, 400, config.tau_s);
  ASSERT_FALSE(r.after.empty());
  size_t old_full = r.before.size() - 1;
  while (r.before[old_full].message.kind != MessageKind::kFull) --old_full;
  StreamReceiver receiver(config, 2, 1800);
  std::vector<ReceivedPosition> got;
  for (const Sent& s : r.before) append(&got, receiver.receive(s.message, static_cast<double>(s.sample.time_s)));
  for (size_t i = 0; i < r.after.size(); ++i) {
    const double now = static_cast<double>(r.after[i].sample.time_s);
    append(&got, receiver.receive(r.after[i].message, now));
    if (i == 10) {
      ASSERT_GT(sequence_distance(r.before[old_full].message.sequence, r.after[i].message.sequence), 1);
      EXPECT_TRUE(receiver.receive(r.before[old_full].message, now).empty());
      EXPECT_EQ(receiver.held(), 0u);
    }
  }
  std::vector<Sent> all = r.before;
  all.insert(all.end(), r.after.begin(), r.after.end());
  expect_positions(got, all, config);  // 400 tau later: past the gap timeout
  EXPECT_EQ(receiver.counters().fresh_starts, 1u);
  EXPECT_EQ(receiver.counters().gaps_skipped, 0u);
}

TEST(StreamLinkTest, ReceiverRestoredMidStreamWithHeldMessagesContinues) {
  TelemetryConfig config;
  StreamSender sender(config, 2, 1);
  const std::vector<Sent> sent = send_all(sender, track_samples(eval::TrackKind::kAuv, 4, 2 * 3600, config.tau_s));
  StreamReceiver receiver(config, 2, 1800);
  std::vector<ReceivedPosition> got;
  for (size_t i = 0; i < 200; ++i) append(&got, receiver.receive(sent[i].message, 0 + kEpoch));
  // 200 lost for now; 201..210 arrive and are held.
  for (size_t i = 201; i <= 210; ++i) append(&got, receiver.receive(sent[i].message, kEpoch));
  EXPECT_EQ(receiver.held(), 10u);
  StreamReceiver restarted(config, 2, 1800);
  ASSERT_TRUE(restarted.restore(receiver.state()));
  EXPECT_EQ(restarted.held(), 10u);
  for (size_t i = 200; i < sent.size(); ++i) append(&got, restarted.receive(sent[i].message, kEpoch));
  expect_positions(got, sent, config);
}

// The link closed: what the receiver asks for reaches the sender before
// its next message. The full past the gap gives its position, but the
// statistics it carries include the lost delta: the receiver asks once, and
// from the sender's next (fresh) full on everything arrives.
TEST(StreamLinkTest, GapThatNeverFillsIsSkippedAtTheNextFullAfterTheTimeout) {
  TelemetryConfig config;
  config.full_every = 20;
  StreamSender sender(config, 2, 1);
  const std::vector<Sample> samples = track_samples(eval::TrackKind::kAuv, 6, 3600, config.tau_s);
  StreamReceiver receiver(config, 2, /*gap_timeout_s=*/100);
  std::vector<Sent> sent;
  std::vector<ReceivedPosition> got;
  const size_t lost = 5;  // a delta the sender gave up on
  std::optional<size_t> fresh;
  double now = kEpoch;
  for (size_t i = 0; i < samples.size(); ++i) {
    sent.push_back({sender.send(samples[i]), samples[i]});
    if (i == lost) {
      ASSERT_EQ(sent[i].message.kind, MessageKind::kDelta);
      continue;
    }
    now += 10;
    append(&got, receiver.receive(sent[i].message, now));
    if (std::optional<Feedback> ask = receiver.take_feedback()) {
      ASSERT_FALSE(fresh) << "asked once, at " << i;
      ASSERT_TRUE(sender.on_feedback(ask->heard));
      fresh = i + 1;
    }
  }
  ASSERT_TRUE(fresh);
  ASSERT_LT(*fresh, sent.size());
  EXPECT_EQ(sent[*fresh].message.kind, MessageKind::kFull);
  EXPECT_EQ(receiver.counters().gaps_skipped, 1u);
  size_t next_full = lost + 1;
  while (sent[next_full].message.kind != MessageKind::kFull) ++next_full;
  // Everything but the lost one, the deltas that depended on it and those
  // until the fresh full, each exactly as sent.
  std::vector<Sent> expected(sent.begin(), sent.begin() + lost);
  expected.push_back(sent[next_full]);
  expected.insert(expected.end(), sent.begin() + static_cast<long>(*fresh), sent.end());
  expect_positions(got, expected, config);
}

TEST(StreamLinkTest, DeltaOfAnotherConfigIsNotDecodedAsAPosition) {
  TelemetryConfig config;
  TelemetryConfig other = config;
  other.model = ModelKind::kUniform;
  StreamSender sender(other, 2, 1);
  StreamReceiver receiver(config, 2, 1800);
  const std::vector<Sent> sent = send_all(sender, track_samples(eval::TrackKind::kAuv, 8, 600, config.tau_s));
  std::vector<ReceivedPosition> got;
  for (const Sent& s : sent) append(&got, receiver.receive(s.message, kEpoch));
  // The full decodes (it does not depend on the model); the deltas are read
  // with tables they were not coded with: whatever comes out is never
  // reported past a body that does not end where it should.
  ASSERT_FALSE(got.empty());
  EXPECT_TRUE(got.front().full);
}

TEST(StreamLinkTest, WireMessagesRoundTripThroughTheShippedDcclTypes) {
  dccl::Codec codec;
  codec.load("acomms/telemetry/messages.proto");
  TelemetryConfig config;
  StreamSender sender(config, 2, 1);
  StreamReceiver receiver(config, 2, 1800);
  const std::vector<Sent> sent = send_all(sender, track_samples(eval::TrackKind::kAuv, 1, 3600, config.tau_s));
  std::vector<ReceivedPosition> got;
  size_t delta_bytes = 0, deltas = 0;
  for (const Sent& s : sent) {
    const std::string bytes = codec.encode(*to_dccl(codec, s.message));
    EXPECT_EQ(codec.id_of(bytes), s.message.kind == MessageKind::kFull ? kFullId : kDeltaId);
    if (s.message.kind == MessageKind::kDelta) {
      delta_bytes += bytes.size();
      ++deltas;
    }
    WireMessage back = from_dccl(*codec.decode(bytes).at(0));
    EXPECT_EQ(back.body, s.message.body);
    EXPECT_EQ(back.sequence, s.message.sequence);
    EXPECT_EQ(back.dest, 1);
    append(&got, receiver.receive(back, static_cast<double>(s.sample.time_s)));
  }
  expect_positions(got, sent, config);
  // id 8 bits + src, dest 7 + sequence 12 + count 7 + codeword, the body
  // padded to a byte: about 7 bytes on an AUV's track (against 12 for
  // three raw 32-bit floats).
  ASSERT_GT(deltas, 0u);
  EXPECT_LE(static_cast<double>(delta_bytes) / static_cast<double>(deltas), 7.25);
}

TEST(StreamLinkTest, SequenceDistanceIsSignedModulo4096) {
  EXPECT_EQ(sequence_distance(1, 0), 1);
  EXPECT_EQ(sequence_distance(0, 4095), 1);
  EXPECT_EQ(sequence_distance(4095, 0), -1);
  EXPECT_EQ(sequence_distance(5, 5), 0);
  EXPECT_EQ(sequence_distance(2048, 0), -2048);
  EXPECT_EQ(sequence_distance(2047, 0), 2047);
}

}  // namespace
}  // namespace acomms::telemetry
