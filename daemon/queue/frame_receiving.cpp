// The receive side: a received frame back into messages for this node.
//
// A frame is DCCL messages end to end with no lengths between them, so it
// is unstitched by decoding: each message's id says its type, and decoding
// it says where the next begins. Bytes that do not decode end the frame
// (nothing after them can be found); what came before is kept. Messages for
// another node are left out unless the queue config is promiscuous, a
// message stamped longer ago than its type's window allows is refused as
// stale, and a retransmission (a sender that missed our ack sends again) is
// recognised by the type's duplicate filter and passed on only once (the
// rule in full: queue_manager.h). Core thread only.

#include <spdlog/spdlog.h>

#include <string>
#include <vector>

#include "core/core_thread.h"
#include "queue/queue_manager.h"

namespace acomms::queue {

std::vector<ReceivedMessage> QueueManager::receive(std::string_view frame, int32_t transmission_src,
                                                   std::optional<std::string_view> link_figures) {
  ACOMMS_ASSERT_CORE_THREAD();
  double now = clock_.now_seconds();
  std::vector<ReceivedMessage> out;
  size_t offset = 0;
  while (offset < frame.size()) {
    std::string_view rest = frame.substr(offset);
    try {
      const dccl::TypeInfo* info = codec_.find_id(codec_.id_of(rest));
      if (info == nullptr) throw dccl::decode_error("unknown DCCL id " + std::to_string(codec_.id_of(rest)));
      size_t used = 0;
      ReceivedMessage received;
      received.message = codec_.decode_as(info->name, rest, &used);
      if (used == 0) throw dccl::decode_error(info->name + " used no bytes");
      offset += used;
      received.type = info->name;
      received.time = now;
      auto state_it = by_name_.find(info->name);
      if (state_it == by_name_.end()) continue;
      TypeState& state = *state_it->second;
      received.dest = state.roles.destination(*received.message);
      int32_t src = state.roles.source(*received.message);
      received.src = src >= 0 ? src : transmission_src;
      if (!promiscuous_ && received.dest != own_id_ && received.dest != kBroadcast) {
        spdlog::debug("queue {}: received message for node {}, not for us", info->name, received.dest);
        continue;
      }
      received.encoded.assign(rest.substr(0, used));
      if (refuse_if_stale(state, received, now) || drop_if_duplicate(state, received, now)) continue;
      JournalMessage as_event;
      as_event.src = received.src;
      as_event.dest = received.dest;
      emit(QueueEventKind::kReceived, state, as_event, now, 0, "", false, false, received.encoded, link_figures);
      received.seq = last_received_seq();  // the number emit() just gave it
      out.push_back(std::move(received));
    } catch (const dccl::Error& e) {
      // DCCL has no length fields: after bytes that do not decode, nothing
      // later in the frame can be found.
      ++malformed_frames_;
      spdlog::warn("queue: received frame from {} undecodable at byte {} of {} ({}): rest dropped",
                   transmission_src, offset, frame.size(), e.what());
      break;
    }
  }
  return out;
}

bool QueueManager::refuse_if_stale(TypeState& state, const ReceivedMessage& received, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!state.filter) return false;
  std::optional<double> stamped = state.roles.timestamp(*received.message);
  double bound = state.window_s + clock_skew_s_;
  if (!stamped || *stamped >= now - bound) {
    if (state.stale_in_burst > 0) {
      spdlog::info("queue {}: {} stale message{} refused before this fresh one", received.type,
                   state.stale_in_burst, state.stale_in_burst == 1 ? "" : "s");
      state.stale_in_burst = 0;
    }
    return false;
  }
  ++stale_refused_;
  // Once per burst: a sender resending a backlog would fill the log.
  if (state.stale_in_burst++ == 0) {
    spdlog::warn("queue {}: message from {} stamped {:.0f} s ago, longer than the type's window of {} s plus "
                 "{} s clock skew: refused as stale, not delivered (a resend whose first copy may already have "
                 "been); further stale ones are counted until a fresh one arrives",
                 received.type, received.src, now - *stamped, state.window_s, clock_skew_s_);
  }
  return true;
}

bool QueueManager::drop_if_duplicate(TypeState& state, const ReceivedMessage& received, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!state.filter) return false;
  DuplicateFilter& filter = *state.filter;
  bool seen = filter.seen(received.src, received.encoded, now);
  if (filter.forgotten_early() > state.forgotten_early_logged) {
    // Logged at the first and then every 1000th: the filter is too small
    // for this rate, and a resend of a forgotten message would be delivered.
    if (state.forgotten_early_logged == 0 || filter.forgotten_early() / 1000 > state.forgotten_early_logged / 1000) {
      spdlog::warn("queue {}: {} received message{} forgotten inside the {} s duplicate window (capacity {}): "
                   "a resend of them would be delivered again", received.type, filter.forgotten_early(),
                   filter.forgotten_early() == 1 ? "" : "s", filter.window_s(), filter.capacity());
    }
    state.forgotten_early_logged = filter.forgotten_early();
  }
  if (!seen) return false;
  ++duplicates_;
  spdlog::info("queue {}: retransmission from {} not passed on again", received.type, received.src);
  return true;
}

}  // namespace acomms::queue
