// Events: the event log, what happened to messages.
#include <spdlog/spdlog.h>

#include <cmath>

#include "service/acomms_service.h"
#include "service/rpc_status.h"

namespace acomms::service {

grpc::Status AcommsService::Events(grpc::ServerContext* context, const v1::EventsRequest* request,
                                   v1::EventsResponse* response) {
  if (grpc::Status denied = allowed(*context, "Events"); !denied.ok()) return denied;
  using grpc::StatusCode;
  size_t limit = 0;
  if (grpc::Status refused = page_limit(request->limit(), &limit); !refused.ok()) return refused;
  if (!std::isfinite(request->since()) || !std::isfinite(request->until()) || request->since() < 0 ||
      request->until() < 0) {
    return {StatusCode::INVALID_ARGUMENT, "since and until are seconds since the Unix epoch (0: unbounded)"};
  }
  if (request->until() > 0 && request->since() > request->until()) {
    return {StatusCode::INVALID_ARGUMENT, "since is after until"};
  }
  if (request->kinds_size() + request->types_size() > 1000) {
    return {StatusCode::INVALID_ARGUMENT, "at most 1000 kinds and types in all"};
  }
  queue::EventQuery query;
  query.since = request->since();
  query.until = request->until();
  query.kinds.assign(request->kinds().begin(), request->kinds().end());
  query.types.assign(request->types().begin(), request->types().end());
  query.message_id = request->message_id();
  query.limit = limit;
  queue::EventPage page;
  try {
    page = node_.events.query(query);
  } catch (const std::invalid_argument& e) {
    return {StatusCode::INVALID_ARGUMENT, e.what()};
  } catch (const std::exception& e) {
    return {StatusCode::UNAVAILABLE, std::string("event log: ") + e.what()};
  }
  for (const queue::LoggedEvent& logged : page.events) {
    const queue::QueueEvent& e = logged.event;
    v1::Event* out = response->add_events();
    out->set_id(logged.id);
    out->set_time(e.time);
    out->set_kind(std::string(queue::to_string(e.kind)));
    out->set_type(e.type);
    out->set_message_id(e.message_id);
    out->set_frame_id(e.frame_id);
    out->set_src(e.src);
    out->set_dest(e.dest);
    out->set_detail(e.detail);
    if (e.link_figures && !out->mutable_link()->ParseFromString(*e.link_figures)) {
      out->clear_link();
      spdlog::warn("events: stored link figures of event {} do not parse: shown without them", logged.id);
    }
  }
  response->set_truncated(page.truncated);
  return grpc::Status::OK;
}

}  // namespace acomms::service
