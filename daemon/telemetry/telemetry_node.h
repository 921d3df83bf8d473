#pragma once
// Position telemetry in acommsd: the vehicle's navigation in, one stream to
// each configured receiver out through the queues; received telemetry
// messages in, reconstructed positions out to the store and subscribers.
//
// The problem: both ends must survive SIGKILL at any moment and continue
// their streams without ever decoding a delta against the wrong state, at
// the cost of at most one full transmission per restart.
//
// The decisions:
// - Sender: each stream's state (stream_sender.h) is posted to the store
//   writer after its message is submitted; the writer commits in order,
//   so the stored state is never ahead of the queue (no phantom gap for the
//   receiver to wait on); at start each stream continues after the newest
//   sequence its queue still holds. After a restart the sampler starts a
//   new segment: the first sample is a full.
// - Receiver: the queue logs every received message (event log, with its
//   bytes) before it reaches us; each stream's state, the positions it
//   produced and the seq of the last event consumed (telemetry_progress)
//   are written after it, in one request. At start the streams are
//   restored and the received telemetry events after that seq are
//   consumed again, so a kill between the two writes loses nothing.
//   Positions are published once they are stored.
// - Statistics outlive fulls: a receiver that lost them queues a
//   PositionFeedback to the sender (stream_receiver.h), which the sender
//   answers with a fresh full; the sender's state after it is stored with
//   the progress, so a feedback consumed is never consumed twice.
//
// Core thread, but for read_state() (before the writer owns the store) and
// the publish callback (the writer's thread).

#include <google/protobuf/message.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/node_position.h"
#include "dccl/codec.h"
#include "queue/event_log_reader.h"
#include "queue/queue_manager.h"
#include "store/group_commit_writer.h"
#include "telemetry/node_settings.h"
#include "telemetry/sampler.h"
#include "telemetry/sequence_gaps.h"
#include "telemetry/stream_receiver.h"
#include "telemetry/stream_sender.h"

namespace acomms::telemetry {

// What the store holds for the streams (migrations/0006_telemetry.sql).
struct StoredStreams {
  std::map<int32_t, std::string> senders;    // receiver -> state
  std::map<int32_t, std::string> receivers;  // sender -> state
  int64_t last_received_seq = 0;
};

struct NodeCounters {
  uint64_t fixes = 0;
  uint64_t fixes_ignored = 0;  // time not after the previous fix
  uint64_t samples = 0;
  uint64_t samples_outside_region = 0;
  uint64_t messages_queued = 0;
  uint64_t fulls_sent = 0;
  uint64_t messages_refused = 0;  // the queue or the store refused them
  uint64_t received = 0;
  uint64_t malformed = 0;  // telemetry types with fields out of range
  uint64_t not_for_us = 0;
  uint64_t feedback_sent = 0;      // requests for a fresh full, to senders
  uint64_t feedback_received = 0;  // from receivers
  uint64_t fresh_requested = 0;    // feedback that made the next full fresh
};

class TelemetryNode {
 public:
  // Queues a telemetry DCCL message; `queued` runs on the core thread with
  // whether it was queued.
  using Submit = std::function<void(std::unique_ptr<google::protobuf::Message> message,
                                    std::function<void(bool queued)> done)>;
  // Positions just stored, in order: runs on the store writer's thread.
  using Publish = std::function<void(const std::vector<ReceivedPosition>& positions)>;

  // `codec` (with messages.proto loaded), `writer` and `position` must
  // outlive the node. Throws std::invalid_argument for invalid settings.
  TelemetryNode(NodeSettings settings, int32_t own_id, const dccl::Codec& codec, store::GroupCommitWriter& writer,
                core::NodePosition* position, Submit submit, Publish publish);

  // Numbers each reconstructed position from the node's received sequence
  // (queue::QueueManager::take_received_seq), so that Subscribe's `after`
  // replays Positions in their place among received messages. Without it
  // (tests of the streams alone) positions carry seq 0. Core thread, before
  // restore().
  using NextSeq = std::function<int64_t()>;
  void number_positions_with(NextSeq next_seq) { next_seq_ = std::move(next_seq); }

  // Before the writer starts on `db`.
  static StoredStreams read_state(store::Database& db);
  // Brings the streams back (senders continue after what `queues` still
  // holds for them), then consumes the received telemetry events the state
  // does not cover yet. Core thread, after the queues restored, before the
  // link starts.
  void restore(const StoredStreams& stored, queue::EventLogReader& events, const queue::QueueManager& queues);

  // A navigation fix in local metres (z up). Samples it and queues a
  // message per receiver for each sample. Returns the messages queued.
  // Throws std::invalid_argument for a non-finite field.
  size_t on_fix(const Fix& fix);

  // `stored` runs (on the store writer's thread) once everything queued so
  // far, messages and stream states, is committed, with why not if not.
  void when_stored(std::function<void(std::exception_ptr)> stored);

  // A message the queue received (any type: others are ignored).
  void on_received(const queue::ReceivedMessage& message);

  // Each stream message received from `src` (to this node) after it was
  // consumed: `missing` messages of that stream before it never arrived
  // (telemetry/sequence_gaps.h; 0 for most); `replayed` when it is
  // consumed again from the event log at start (its gap, if any, was told
  // when it first came: not to be counted again). Core thread.
  using OnSequence = std::function<void(int32_t src, uint32_t missing, bool replayed)>;
  void on_sequence(OnSequence on_sequence) { on_sequence_ = std::move(on_sequence); }
  const SequenceGapCounters& sequence_gaps() const { return gaps_.counters(); }

  const NodeSettings& settings() const { return settings_; }
  const NodeCounters& counters() const { return counters_; }

 private:
  StreamReceiver& receiver_for(int32_t src);
  void consume(const WireMessage& message, int64_t event_seq, double now);
  void on_feedback(const WireFeedback& feedback, int64_t event_seq);
  // Queues the feedback `receiver` has due, if any.
  void send_feedback(int32_t src, StreamReceiver& receiver);
  // Posts a sender's state (and, with event_seq, the progress) to the writer.
  void save_sender(int32_t receiver, const StreamSender& sender, std::optional<int64_t> event_seq);

  NodeSettings settings_;
  int32_t own_id_;
  const dccl::Codec& codec_;
  store::GroupCommitWriter& writer_;
  core::NodePosition* position_;
  Submit submit_;
  Publish publish_;
  NextSeq next_seq_;
  Sampler sampler_;
  std::map<int32_t, StreamSender> senders_;
  std::map<int32_t, StreamReceiver> receivers_;
  int64_t last_event_seq_ = 0;
  std::optional<double> last_fix_time_s_;
  NodeCounters counters_;
  SequenceGaps gaps_;
  OnSequence on_sequence_;
  bool replaying_ = false;  // restore() consumes stored messages again
};

}  // namespace acomms::telemetry
