// The receive side: a received frame back into messages for this node.
//
// A frame is DCCL messages end to end with no lengths between them, so it
// is unstitched by decoding: each message's id says its type, and decoding
// it says where the next begins. Bytes that do not decode end the frame
// (nothing after them can be found); what came before is kept. Messages for
// another node are left out unless the queue config is promiscuous; the
// rest go through the ReceiveFilter (receive_filter.h: stale ones and
// retransmissions are not passed on). Messages of authenticated types
// (dccl/message_auth.h) must first show a tag that verifies, a stamp inside
// their window and bytes not accepted before (auth_guard.h). Core thread
// only.

#include <spdlog/spdlog.h>

#include <string>
#include <vector>

#include "core/core_thread.h"
#include "queue/queue_manager.h"

namespace acomms::queue {

std::vector<ReceivedMessage> QueueManager::receive(std::string_view frame, int32_t transmission_src,
                                                   std::optional<std::string_view> link_figures, int link,
                                                   int32_t transmission_dest) {
  ACOMMS_ASSERT_CORE_THREAD();
  double now = clock_.now_seconds();
  std::vector<ReceivedMessage> out;
  // Any frame from a node (an empty one too) says this link reaches it.
  if (routing_ != nullptr) routing_->heard(link, transmission_src, now);
  size_t offset = 0;
  while (offset < frame.size()) {
    std::string_view rest = frame.substr(offset);
    try {
      // A routing envelope (queue/routing.h): routing reads it, this
      // node never decodes what it carries for others.
      if (routing_ != nullptr && codec_.id_of(rest) == static_cast<int>(routing_->envelope_id())) {
        EnvelopeOutcome outcome = routing_->on_envelope(rest, transmission_src, transmission_dest, link, link_figures, now);
        if (outcome.used == 0) throw dccl::decode_error("malformed routing envelope");
        if (outcome.ack_only_if) ack_conditions_.push_back(std::move(outcome.ack_only_if));
        for (ReceivedMessage& m : outcome.delivered) out.push_back(std::move(m));
        offset += outcome.used;
        continue;
      }
      // The node's piggyback (queue/piggyback.h): last in its frame.
      if (piggyback_ != nullptr && codec_.id_of(rest) == static_cast<int>(piggyback_->dccl_id())) {
        const size_t used = piggyback_->on_received(rest, transmission_src, link, now);
        if (used == 0) throw dccl::decode_error("malformed piggyback");
        offset += used;
        continue;
      }
      const dccl::TypeInfo* info = codec_.find_id(codec_.id_of(rest));
      if (info == nullptr) throw dccl::decode_error("unknown DCCL id " + std::to_string(codec_.id_of(rest)));
      size_t used = 0;
      ReceivedMessage received;
      // Either says so: a type the codec seals but no window was given for
      // fails closed (every stamp is outside a window of 0).
      const bool authenticated = codec_.authenticated(info->name) || auth_guard_.covers(info->name);
      try {
        received.message = codec_.decode_as(info->name, rest, &used);
      } catch (const dccl::Error& e) {
        // A truncated trailer, or bytes that are not this type at all: no
        // verified tag, so nothing after it can be trusted either.
        if (!authenticated) throw;
        auth_guard_.refuse(AuthRefusal::kAuthFailed, info->name, transmission_src, e.what(), now);
        break;
      }
      if (used == 0) throw dccl::decode_error(info->name + " used no bytes");
      offset += used;
      received.type = info->name;
      received.time = now;
      auto state_it = by_name_.find(info->name);
      if (state_it == by_name_.end()) continue;
      TypeState& state = *state_it->second;
      std::optional<dccl::AuthStamp> stamp;
      if (authenticated && !(stamp = admit_authenticated(info->name, rest.substr(0, used), transmission_src, now))) {
        continue;  // refused, counted and logged: never reaches a subscriber
      }
      received.dest = state.roles.destination(*received.message);
      int32_t src = state.roles.source(*received.message);
      received.src = src >= 0 ? src : transmission_src;
      if (!promiscuous_ && received.dest != own_id_ && received.dest != kBroadcast) {
        spdlog::debug("queue {}: received message for node {}, not for us", info->name, received.dest);
        continue;
      }
      received.encoded.assign(rest.substr(0, used));
      if (!receive_filter_.admit(received, state.roles, now)) continue;
      JournalMessage as_event;
      as_event.src = received.src;
      as_event.dest = received.dest;
      if (stamp) auth_guard_.remember(info->name, transmission_src, received.encoded, stamp->sent_s, now);
      emit(state, now, {.kind = QueueEventKind::kReceived, .message = as_event, .encoded = received.encoded,
                        .link_figures = link_figures,
                        .auth_sent_s = stamp ? std::optional<uint32_t>(stamp->sent_s) : std::nullopt,
                        .auth_sender = transmission_src});
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

std::optional<dccl::AuthStamp> QueueManager::admit_authenticated(const std::string& type, std::string_view message,
                                                                int32_t transmission_src, double now) {
  dccl::AuthStamp stamp;
  const dccl::MessageAuthenticator* authenticator = codec_.authenticator();
  const dccl::AuthVerdict verdict =
      authenticator ? authenticator->verify(message, now, transmission_src, &stamp) : dccl::AuthVerdict::kUnknownKey;
  if (verdict != dccl::AuthVerdict::kOk) {
    std::string detail(dccl::to_string(verdict));
    if (verdict == dccl::AuthVerdict::kUnknownKey || verdict == dccl::AuthVerdict::kKeyRetired) {
      // The key id is the trailer's first byte (present: not kTruncated).
      const size_t trailer = authenticator ? authenticator->trailer_bytes() : message.size();
      detail += " " + std::to_string(static_cast<uint8_t>(message[message.size() - trailer]));
    }
    auth_guard_.refuse(AuthRefusal::kAuthFailed, type, transmission_src, detail, now);
    return std::nullopt;
  }
  if (auto why = auth_guard_.judge(type, transmission_src, message, stamp, now)) {
    std::string detail = "stamped " + std::to_string(static_cast<int64_t>(now) - int64_t{stamp.sent_s}) + " s ago";
    auth_guard_.refuse(*why, type, transmission_src, detail, now);
    return std::nullopt;
  }
  return stamp;
}

}  // namespace acomms::queue
