// Subscribe: received messages streamed to a client, optionally resuming
// from the store after a sequence number the client last handled.
//
// The seam between replay and live, and why it has neither gap nor
// duplicate:
//  1. A message is published to live subscriptions only after its event,
//     carrying its seq, is committed (node/received_message_router.h), and
//     messages are published in seq order.
//  2. The stream subscribes to live messages *before* it reads the store.
//     So every message is either committed before a replay read (and the
//     read finds it) or committed after it, and then published after the
//     subscription exists (and it is in the live buffer). Nothing falls
//     between.
//  3. Replay ends when a read finds nothing newer; `cursor` is then the
//     last seq written. Live messages with seq <= cursor were replayed
//     already and are skipped; the rest are newer, in order.
//  4. Telemetry's Positions are numbered in the same sequence (they are
//     stored in telemetry_position, committed and published like received
//     messages: telemetry/telemetry_node.h), so replay merges the two
//     tables in seq order.
// INVARIANT: the seqs written to one stream strictly increase (leaving out
// seq 0: driver-specific receptions, which are not stored).
#include <spdlog/spdlog.h>

#include <google/protobuf/descriptor.h>

#include <algorithm>

#include "dccl/message_json.h"
#include "service/acomms_service.h"
#include "service/position_message.h"
#include "service/replay_merge.h"
#include "telemetry/wire_message.h"
#include "service/rpc_status.h"

namespace acomms::service {
namespace {

// How often a waiting stream checks whether its client went away.
constexpr std::chrono::milliseconds kPollCancel(200);
// Stored messages read per query while replaying.
constexpr size_t kReplayPage = 256;

v1::ReceivedMessage from_store(const queue::StoredReceived& stored, const dccl::Codec& codec) {
  v1::ReceivedMessage out;
  out.set_type(stored.type);
  out.set_src(stored.src);
  out.set_dest(stored.dest < 0 ? 0 : stored.dest);
  out.set_receive_time(stored.time);
  out.set_seq(stored.seq);
  // The figures it carried live (none for rows older than migration 0008).
  if (stored.link_figures && !out.mutable_link()->ParseFromString(*stored.link_figures)) {
    out.clear_link();
    spdlog::warn("subscribe: stored link figures of seq {} do not parse: replayed without them", stored.seq);
  }
  try {
    auto message = codec.decode_as(stored.type, stored.encoded);
    out.set_payload(message->SerializePartialAsString());
    out.set_json(dccl::message_json(*message));
  } catch (const std::exception& e) {
    // Still sent (with no payload): a resuming client must see every seq.
    spdlog::warn("subscribe: stored message seq {} of type {} no longer decodes: {}", stored.seq, stored.type,
                 e.what());
  }
  return out;
}

// What a driver reports as received outside DCCL (a Micro-Modem mini-packet:
// link/driver_specific.h) arrives under its own message type, compiled in
// with the driver's proto (api/proto/acomms/drivers/).
bool is_driver_specific_type(const std::string& type) {
  return type.starts_with("acomms.drivers.") &&
         google::protobuf::DescriptorPool::generated_pool()->FindMessageTypeByName(type) != nullptr;
}

bool filter_has_position(const std::vector<std::string>& types) {
  return std::find(types.begin(), types.end(), kPositionType) != types.end();
}

}  // namespace

// A stored position as it was published live (daemon: node/daemon.cpp).
v1::ReceivedMessage AcommsService::from_track(const telemetry::ReceivedPosition& position) const {
  return to_received_message(to_position(position, node_.telemetry.settings()),
                             static_cast<int32_t>(identity_.modem_id), position.received_s, position.seq);
}

grpc::Status AcommsService::Subscribe(grpc::ServerContext* context, const v1::SubscribeRequest* request,
                                      grpc::ServerWriter<v1::ReceivedMessage>* writer) {
  if (grpc::Status denied = allowed(*context, "Subscribe"); !denied.ok()) return denied;
  Subscription::Filter filter;
  {
    auto stable = node_.submitter.types_stable();
    for (const std::string& type : request->types()) {
      // Position is what telemetry publishes, not a DCCL type.
      if (node_.codec.find_type(type) == nullptr && !is_driver_specific_type(type) &&
          type != kPositionType) {
        return type_not_loaded(type);
      }
      filter.types.insert(type);
    }
  }
  if (request->has_src()) filter.src = request->src();
  const std::vector<std::string> types(filter.types.begin(), filter.types.end());
  const std::optional<int32_t> src = filter.src;
  // Live first (seam step 2), then the store.
  std::shared_ptr<Subscription> subscription = node_.subscribers.subscribe(std::move(filter));
  int64_t cursor = 0;
  if (request->has_after()) {
    cursor = request->after();
    if (cursor < 0) {
      node_.subscribers.unsubscribe(subscription);
      return {grpc::StatusCode::INVALID_ARGUMENT, "after must be 0 or more (got " + std::to_string(cursor) + ")"};
    }
    queue::ReceivedRange range = node_.events.received_range();
    if (!range.replayable_after(cursor)) {
      node_.subscribers.unsubscribe(subscription);
      return {grpc::StatusCode::OUT_OF_RANGE,
              "received messages after seq " + std::to_string(cursor) + " were pruned; the first still held is " +
                  std::to_string(range.first) + " (store.event_retention_days / event_retention_mb)"};
    }
  }
  // Headers go out now, so the client knows it is subscribed before the
  // first message (tests and tools wait for this).
  writer->SendInitialMetadata();
  grpc::Status result = grpc::Status::OK;
  bool gone = false;
  if (request->has_after()) {
    const bool wants_positions = types.empty() || filter_has_position(types);
    for (;;) {
      std::vector<queue::StoredReceived> page = node_.events.received_after(cursor, types, src, kReplayPage);
      std::vector<telemetry::ReceivedPosition> positions;
      if (wants_positions) positions = node_.track.positions_after(cursor, src, kReplayPage);
      if ((page.empty() && positions.empty()) || context->IsCancelled()) break;
      std::vector<int64_t> message_seqs, position_seqs;
      for (const queue::StoredReceived& stored : page) message_seqs.push_back(stored.seq);
      for (const telemetry::ReceivedPosition& position : positions) position_seqs.push_back(position.seq);
      std::vector<v1::ReceivedMessage> messages;
      {
        // Decoded under the lock, written without it: a slow client must
        // not hold up loading definitions.
        auto stable = node_.submitter.types_stable();
        for (const ReplayPick& pick : merge_replay_pages(message_seqs, page.size() == kReplayPage, position_seqs,
                                                         positions.size() == kReplayPage)) {
          messages.push_back(pick.position ? from_track(positions[pick.index])
                                           : from_store(page[pick.index], node_.codec));
        }
      }
      for (const v1::ReceivedMessage& message : messages) {
        // Telemetry's own messages are never published live (their content
        // comes out as Position): not replayed either.
        if (telemetry::is_telemetry_type(message.type())) {
          cursor = message.seq();
          continue;
        }
        if (!writer->Write(message)) {
          gone = true;
          break;
        }
        cursor = message.seq();
      }
      if (gone) break;
    }
  }
  while (!gone && !context->IsCancelled()) {
    if (std::optional<v1::ReceivedMessage> message = subscription->next(kPollCancel)) {
      // seq 0: not a message of the event log (a driver-specific reception,
      // link/driver_specific.h), never replayed, so never at the seam; it
      // does not move the cursor.
      if (message->seq() != 0 && message->seq() <= cursor) continue;  // replayed already (seam step 3)
      if (!writer->Write(*message)) break;  // the client went away
      if (message->seq() != 0) cursor = message->seq();
      continue;
    }
    if (std::optional<grpc::Status> ended = subscription->ended()) {
      result = *ended;
      break;
    }
  }
  node_.subscribers.unsubscribe(subscription);
  return result;
}

}  // namespace acomms::service
