// ListQueued, Cancel, Flush and QueueStats: what waits for the link.
#include "dccl/message_json.h"
#include "route/forwarder.h"
#include "service/acomms_service.h"
#include "service/rpc_status.h"
#include "util/seconds.h"

namespace acomms::service {
namespace {

v1::QueuePolicy to_proto(const queue::QueuePolicy& policy) {
  v1::QueuePolicy out;
  out.set_ack(policy.ack);
  out.set_blackout_time_s(policy.blackout_time_s);
  out.set_max_queue(policy.max_queue);
  out.set_newest_first(policy.newest_first);
  out.set_ttl_s(policy.ttl_s);
  out.set_value_base(policy.value_base);
  out.set_on_full(policy.on_full == queue::QueuePolicy::OnFull::kRefuseNew ? v1::QueuePolicy::REFUSE_NEW
                                                                          : v1::QueuePolicy::DROP_OLDEST);
  return out;
}

}  // namespace

grpc::Status AcommsService::ListQueued(grpc::ServerContext* context, const v1::ListQueuedRequest* request,
                                       v1::ListQueuedResponse* response) {
  if (grpc::Status denied = allowed(*context, "ListQueued"); !denied.ok()) return denied;
  size_t limit = 0;
  if (grpc::Status refused = page_limit(request->limit(), &limit); !refused.ok()) return refused;
  auto stable = node_.submitter.types_stable();
  if (!request->type().empty() && node_.queues.find_queue(request->type()) == nullptr) {
    return no_queue(request->type());
  }
  // Copied on the core thread (cheap), turned into JSON here (not cheap),
  // so a long listing does not hold up the link.
  struct Row {
    v1::QueuedMessage message;
    std::string payload;
  };
  bool truncated = false;
  std::vector<Row> rows = node_.core.call([&] {
    std::vector<Row> out;
    for (const queue::Queue* queue : node_.queues.queues()) {
      if (!request->type().empty() && queue->type() != request->type()) continue;
      for (const queue::QueuedMessage& queued : queue->messages()) {
        if (out.size() == limit) {
          truncated = true;
          return out;
        }
        Row row;
        v1::QueuedMessage& m = row.message;
        m.set_message_id(queued.record.id);
        m.set_type(queued.record.type);
        m.set_src(queued.record.src);
        m.set_dest(queued.record.dest);
        m.set_submitted_at(queued.record.submitted_at);
        m.set_ttl_s(queue->ttl_of(queued));
        m.set_expires_at(queued.record.submitted_at + queue->ttl_of(queued));
        m.set_in_flight(queued.in_flight_frame != 0);
        m.set_encoded_bytes(static_cast<uint32_t>(queued.encoded.size()));
        if (node_.forwarder != nullptr) {
          m.set_waiting(node_.forwarder->waiting(*queue, queued));
          m.set_json(node_.forwarder->custody_json(*queue, queued));
          // Where it goes next by its route now: what an operator reads
          // as "waits for node 2 on sat" (README "Gateways").
          if (queued.record.dest != queue::kBroadcast) {
            if (std::optional<route::NextHop> next = node_.forwarder->next_hop(queued.record.dest)) {
              m.set_next_hop(next->node);
              m.set_next_link(next->link);
            }
          }
        }
        row.payload = queued.record.payload;
        out.push_back(std::move(row));
      }
    }
    return out;
  });
  for (Row& row : rows) {
    // A gateway's custody queue holds envelopes of types it may not know.
    if (node_.codec.find_type(row.message.type()) == nullptr) {
      *response->add_messages() = std::move(row.message);
      continue;
    }
    std::unique_ptr<google::protobuf::Message> message = node_.codec.new_message(row.message.type());
    if (message->ParsePartialFromString(row.payload)) row.message.set_json(dccl::message_json(*message));
    *response->add_messages() = std::move(row.message);
  }
  response->set_truncated(truncated);
  return grpc::Status::OK;
}

grpc::Status AcommsService::Cancel(grpc::ServerContext* context, const v1::CancelRequest* request, v1::CancelResponse*) {
  if (grpc::Status denied = allowed(*context, "Cancel"); !denied.ok()) return denied;
  if (request->message_id() <= 0) return {grpc::StatusCode::INVALID_ARGUMENT, "message_id must be positive"};
  if (request->reason().size() > 1024) return {grpc::StatusCode::INVALID_ARGUMENT, "reason is longer than 1024 bytes"};
  std::string reason = request->reason().empty() ? "cancelled by client" : request->reason();
  bool cancelled = node_.core.call([&] { return node_.queues.cancel(request->message_id(), reason); });
  if (!cancelled) {
    return {grpc::StatusCode::NOT_FOUND,
            "message " + std::to_string(request->message_id()) +
                " is not queued (delivered, expired, dropped, or never submitted: see `acommsctl events --message " +
                std::to_string(request->message_id()) + "`)"};
  }
  return grpc::Status::OK;
}

grpc::Status AcommsService::Flush(grpc::ServerContext* context, const v1::FlushRequest* request,
                                  v1::FlushResponse* response) {
  if (grpc::Status denied = allowed(*context, "Flush"); !denied.ok()) return denied;
  if (request->type().empty()) return {grpc::StatusCode::INVALID_ARGUMENT, "name the type whose queue to flush"};
  auto stable = node_.submitter.types_stable();
  try {
    size_t removed = node_.core.call([&] { return node_.queues.flush(request->type(), "flushed by client"); });
    response->set_removed(static_cast<uint32_t>(removed));
  } catch (const queue::UnknownTypeError&) {
    return no_queue(request->type());
  }
  return grpc::Status::OK;
}

grpc::Status AcommsService::QueueStats(grpc::ServerContext* context, const v1::QueueStatsRequest* request,
                                       v1::QueueStatsResponse* response) {
  if (grpc::Status denied = allowed(*context, "QueueStats"); !denied.ok()) return denied;
  auto stable = node_.submitter.types_stable();
  for (const std::string& type : request->types()) {
    if (node_.queues.find_queue(type) == nullptr) {
      return no_queue(type);
    }
  }
  std::set<std::string> wanted(request->types().begin(), request->types().end());
  node_.core.call([&] {
    double now = util::unix_seconds_now();
    for (const queue::Queue* queue : node_.queues.queues()) {
      if (!wanted.empty() && wanted.count(queue->type()) == 0) continue;
      const queue::QueueStats stats = node_.queues.stats(queue->type());
      v1::QueueStatsEntry* entry = response->add_queues();
      entry->set_type(queue->type());
      entry->set_dccl_id(queue->dccl_id());
      entry->set_size(static_cast<uint32_t>(queue->size()));
      entry->set_in_flight(static_cast<uint32_t>(queue->in_flight()));
      entry->set_priority(queue->priority(now));
      entry->set_last_sent(stats.sent > 0 ? queue->last_sent() : 0);
      entry->set_queued(stats.queued);
      entry->set_sent(stats.sent);
      entry->set_acked(stats.acked);
      entry->set_expired(stats.expired);
      entry->set_dropped(stats.dropped);
      entry->set_retried(stats.retried);
      entry->set_received(stats.received);
      entry->set_refused(stats.refused);
      entry->set_delivered(stats.delivered);
      entry->set_expired_remote(stats.expired_remote);
      *entry->mutable_policy() = to_proto(queue->policy());
    }
  });
  return grpc::Status::OK;
}

}  // namespace acomms::service
