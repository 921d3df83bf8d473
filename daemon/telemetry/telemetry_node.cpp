#include "telemetry/telemetry_node.h"

#include <spdlog/spdlog.h>

#include <stdexcept>

#include "core/core_thread.h"
#include "dccl/error.h"

namespace acomms::telemetry {

TelemetryNode::TelemetryNode(NodeSettings settings, int32_t own_id, const dccl::Codec& codec,
                             store::GroupCommitWriter& writer, core::NodePosition* position, Submit submit,
                             Publish publish)
    : settings_(std::move(settings)),
      own_id_(own_id),
      codec_(codec),
      writer_(writer),
      position_(position),
      submit_(std::move(submit)),
      publish_(std::move(publish)),
      sampler_(settings_.stream.tau_s) {
  for (int32_t receiver : settings_.receivers) senders_.try_emplace(receiver, settings_.stream, own_id_, receiver);
}

StoredStreams TelemetryNode::read_state(store::Database& db) {
  StoredStreams stored;
  store::Statement senders = db.prepare("SELECT receiver, state FROM telemetry_sender");
  while (senders.step()) stored.senders[static_cast<int32_t>(senders.column_int64(0))] = senders.column_blob(1);
  store::Statement receivers = db.prepare("SELECT sender, state FROM telemetry_receiver");
  while (receivers.step())
    stored.receivers[static_cast<int32_t>(receivers.column_int64(0))] = receivers.column_blob(1);
  store::Statement progress = db.prepare("SELECT last_seq FROM telemetry_progress WHERE name = 'received'");
  if (progress.step()) stored.last_received_seq = progress.column_int64(0);
  return stored;
}

void TelemetryNode::restore(const StoredStreams& stored, queue::EventLogReader& events,
                            const queue::QueueManager& queues) {
  ACOMMS_ASSERT_CORE_THREAD();
  for (auto& [receiver, sender] : senders_) {
    auto it = stored.senders.find(receiver);
    if (it != stored.senders.end() && !sender.restore(it->second)) {
      spdlog::warn("telemetry to {}: stored state unusable (another telemetry config?): starting over", receiver);
    }
  }
  // A kill between a message's commit and its state's leaves the state one
  // behind the queue: continue after the newest sequence queued.
  for (std::string_view type : {kFullType, kDeltaType}) {
    const queue::Queue* queue = queues.find_queue(std::string(type));
    if (queue == nullptr) continue;
    for (const queue::QueuedMessage& queued : queue->messages()) {
      auto sender = senders_.find(queued.record.dest);
      if (sender == senders_.end()) continue;
      try {
        sender->second.continue_after(from_dccl(*codec_.decode_as(type, queued.encoded)).sequence);
      } catch (const std::exception& e) {
        spdlog::warn("telemetry: queued message {} unreadable ({}): left to the queue", queued.record.id, e.what());
      }
    }
  }
  for (const auto& [src, state] : stored.receivers) {
    if (!receiver_for(src).restore(state)) {
      spdlog::warn("telemetry from {}: stored state unusable: waiting for the next full", src);
    }
  }
  last_event_seq_ = stored.last_received_seq;
  // Received after the last state we stored: consumed again, in order.
  const std::vector<std::string> types{std::string(kFullType), std::string(kDeltaType), std::string(kFeedbackType)};
  size_t replayed = 0;
  for (;;) {
    std::vector<queue::StoredReceived> batch = events.received_after(last_event_seq_, types, std::nullopt, 1000);
    if (batch.empty()) break;
    for (const queue::StoredReceived& stored_message : batch) {
      queue::ReceivedMessage message;
      message.type = stored_message.type;
      message.seq = stored_message.seq;
      message.src = stored_message.src;
      message.dest = stored_message.dest;
      message.time = stored_message.time;
      try {
        message.message = codec_.decode_as(stored_message.type, stored_message.encoded);
      } catch (const dccl::Error& e) {
        spdlog::warn("telemetry: received event {} does not decode any more ({}): skipped", stored_message.seq,
                     e.what());
        last_event_seq_ = stored_message.seq;
        continue;
      }
      replaying_ = true;
      on_received(message);
      replaying_ = false;
      last_event_seq_ = std::max(last_event_seq_, stored_message.seq);
      ++replayed;
    }
  }
  if (replayed > 0) spdlog::info("telemetry: {} received message{} consumed again after a restart", replayed, replayed == 1 ? "" : "s");
  // What this node missed while it was down is no gap (sequence_gaps.h):
  // the first live message from each sender is a new baseline.
  gaps_.forget();
}

size_t TelemetryNode::on_fix(const Fix& fix) {
  ACOMMS_ASSERT_CORE_THREAD();
  std::vector<Sample> samples = sampler_.add(fix);  // throws for a non-finite field
  // The sampler ignores a fix that does not move time forward.
  if (last_fix_time_s_ && fix.time_s <= *last_fix_time_s_) {
    ++counters_.fixes_ignored;
    return 0;
  }
  last_fix_time_s_ = fix.time_s;
  ++counters_.fixes;
  if (position_) position_->set(core::NodeFix{fix.time_s, fix.position_m[0], fix.position_m[1], fix.position_m[2]});
  size_t queued = 0;
  for (const Sample& sample : samples) {
    ++counters_.samples;
    for (auto& [receiver, sender] : senders_) {
      WireMessage message;
      try {
        message = sender.send(sample);
      } catch (const std::out_of_range& e) {
        // Outside the region a full can code: nothing to send. The next
        // sample inside it goes as a full (the encoder did not move).
        ++counters_.samples_outside_region;
        spdlog::warn("telemetry: sample at {} s not sent: {}", sample.time_s, e.what());
        break;
      }
      if (message.kind == MessageKind::kFull) ++counters_.fulls_sent;
      submit_(to_dccl(codec_, message), [this, receiver = receiver](bool ok) {
        ACOMMS_ASSERT_CORE_THREAD();
        if (ok) return;
        ++counters_.messages_refused;
        // The receiver will never see it: whatever follows must not depend on it.
        auto it = senders_.find(receiver);
        if (it != senders_.end()) it->second.request_fresh();
      });
      // The state after the message: the writer commits in order, so the
      // stored state is never ahead of the queue (restore() handles behind).
      save_sender(receiver, sender, std::nullopt);
      ++counters_.messages_queued;
      ++queued;
    }
  }
  return queued;
}

void TelemetryNode::save_sender(int32_t receiver, const StreamSender& sender, std::optional<int64_t> event_seq) {
  writer_.post([this, receiver, state = sender.state(), event_seq](store::Database&) {
    store::Statement& save = writer_.prepared("INSERT OR REPLACE INTO telemetry_sender (receiver, state) VALUES (?, ?)");
    save.bind(1, int64_t{receiver}).bind_blob(2, state);
    save.step();
    save.reset();
    if (!event_seq) return;
    store::Statement& progress =
        writer_.prepared("UPDATE telemetry_progress SET last_seq = max(last_seq, ?) WHERE name = 'received'");
    progress.bind(1, *event_seq);
    progress.step();
    progress.reset();
  });
}

void TelemetryNode::when_stored(std::function<void(std::exception_ptr)> stored) {
  ACOMMS_ASSERT_CORE_THREAD();
  // The writer commits in order: an empty request's commit follows every
  // request queued before it.
  writer_.post([](store::Database&) {}, std::move(stored));
}

void TelemetryNode::send_feedback(int32_t src, StreamReceiver& receiver) {
  std::optional<Feedback> due = receiver.take_feedback();
  if (!due || !submit_) return;
  WireFeedback feedback{own_id_, src, due->heard};
  ++counters_.feedback_sent;
  spdlog::info("telemetry from {}: asking it for a fresh full (statistics not held; last heard {})", src,
               due->heard ? std::to_string(*due->heard) : std::string("nothing"));
  submit_(to_dccl(codec_, feedback), [src](bool ok) {
    // Not queued: the receiver asks again at the next full it consumes.
    if (!ok) spdlog::warn("telemetry from {}: request for a fresh full not queued", src);
  });
}

void TelemetryNode::on_feedback(const WireFeedback& feedback, int64_t event_seq) {
  ++counters_.feedback_received;
  last_event_seq_ = std::max(last_event_seq_, event_seq);
  auto it = senders_.find(feedback.src);
  if (it == senders_.end()) {
    ++counters_.not_for_us;  // no stream to that node (any more)
    return;
  }
  if (it->second.on_feedback(feedback.heard)) {
    ++counters_.fresh_requested;
    spdlog::info("telemetry to {}: it lost the statistics: the next full starts them afresh", feedback.src);
  }
  save_sender(feedback.src, it->second, last_event_seq_);
}

StreamReceiver& TelemetryNode::receiver_for(int32_t src) {
  auto it = receivers_.find(src);
  if (it == receivers_.end()) it = receivers_.try_emplace(src, settings_.stream, src, settings_.gap_timeout_s).first;
  return it->second;
}

void TelemetryNode::on_received(const queue::ReceivedMessage& message) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!is_telemetry_type(message.type) || !message.message) return;
  ++counters_.received;
  if (message.type == kFeedbackType) {
    WireFeedback feedback;
    try {
      feedback = feedback_from_dccl(*message.message);
    } catch (const std::invalid_argument& e) {
      ++counters_.malformed;
      spdlog::warn("telemetry: received {} from {} refused: {}", message.type, message.src, e.what());
      return;
    }
    if (feedback.dest != own_id_) {
      ++counters_.not_for_us;
      return;
    }
    feedback.src = message.src;
    on_feedback(feedback, message.seq);
    return;
  }
  WireMessage wire;
  try {
    wire = from_dccl(*message.message);
  } catch (const std::invalid_argument& e) {
    ++counters_.malformed;
    spdlog::warn("telemetry: received {} from {} refused: {}", message.type, message.src, e.what());
    return;
  }
  if (wire.dest != own_id_) {
    ++counters_.not_for_us;  // promiscuous queues pass on others' streams
    return;
  }
  wire.src = message.src;
  StreamReceiver& receiver = receiver_for(wire.src);
  const uint64_t fresh_starts = receiver.counters().fresh_starts;
  consume(wire, message.seq, message.time);
  const uint32_t missing = gaps_.observe(wire.src, wire.sequence, receiver.counters().fresh_starts != fresh_starts);
  if (on_sequence_) on_sequence_(wire.src, missing, replaying_);
}

void TelemetryNode::consume(const WireMessage& message, int64_t event_seq, double now) {
  StreamReceiver& receiver = receiver_for(message.src);
  std::vector<ReceivedPosition> positions = receiver.receive(message, now);
  for (ReceivedPosition& p : positions) {
    p.received_s = now;
    if (next_seq_) p.seq = next_seq_();
  }
  last_event_seq_ = std::max(last_event_seq_, event_seq);
  // Queued before the state is posted: a kill between the two consumes the
  // message again at restart and asks again (at worst one extra request).
  send_feedback(message.src, receiver);
  writer_.post(
      [this, src = message.src, state = receiver.state(), positions, seq = last_event_seq_](store::Database&) {
        store::Statement& save =
            writer_.prepared("INSERT OR REPLACE INTO telemetry_receiver (sender, state) VALUES (?, ?)");
        save.bind(1, int64_t{src}).bind_blob(2, state);
        save.step();
        save.reset();
        store::Statement& insert = writer_.prepared(
            "INSERT OR REPLACE INTO telemetry_position (src, time, x, y, z, full, seq, received) "
            "VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
        int64_t last_position_seq = 0;
        for (const ReceivedPosition& p : positions) {
          insert.bind(1, int64_t{p.src}).bind_double(2, static_cast<double>(p.time_s));
          insert.bind_double(3, p.position_m[0]).bind_double(4, p.position_m[1]).bind_double(5, p.position_m[2]);
          insert.bind(6, int64_t{p.full ? 1 : 0});
          if (p.seq != 0) {
            insert.bind(7, p.seq);
          } else {
            insert.bind_null(7);
          }
          insert.bind_double(8, p.received_s);
          insert.step();
          insert.reset();
          last_position_seq = std::max(last_position_seq, p.seq);
        }
        if (last_position_seq != 0) {
          // The numbers are the received sequence's (migration 0005): made
          // durable here, with the positions, so a restart never hands one
          // out again.
          store::Statement& advance =
              writer_.prepared("UPDATE event_sequence SET last = MAX(last, ?) WHERE name = 'received'");
          advance.bind(1, last_position_seq);
          advance.step();
          advance.reset();
        }
        store::Statement& progress =
            writer_.prepared("UPDATE telemetry_progress SET last_seq = max(last_seq, ?) WHERE name = 'received'");
        progress.bind(1, seq);
        progress.step();
        progress.reset();
      },
      [this, positions](std::exception_ptr error) mutable {
        if (error) {
          spdlog::error("telemetry: {} position{} not stored; passed on anyway", positions.size(),
                        positions.size() == 1 ? "" : "s");
          // Their numbers were not made durable: a restart may hand them
          // out again, so they go out unnumbered (live only, never resumed).
          for (ReceivedPosition& p : positions) p.seq = 0;
        }
        if (!positions.empty() && publish_) publish_(positions);
      });
}

}  // namespace acomms::telemetry
