// ListRoutes: a gateway's route table and forwarding counters
// (route/forwarder.h), copied on the core thread, which owns them.
#include "route/forwarder.h"
#include "service/acomms_service.h"

namespace acomms::service {

grpc::Status AcommsService::ListRoutes(grpc::ServerContext* context, const v1::ListRoutesRequest*,
                                       v1::ListRoutesResponse* response) {
  if (grpc::Status denied = allowed(*context, "ListRoutes"); !denied.ok()) return denied;
  if (node_.forwarder == nullptr) {
    return {grpc::StatusCode::FAILED_PRECONDITION,
            "this node routes nothing: give it a `routing { ... }` block (README, \"Gateways\")"};
  }
  node_.core.call([&] {
    const route::Forwarder& forwarder = *node_.forwarder;
    for (const route::RouteEntry& entry : forwarder.list_routes()) {
      v1::Route& route = *response->add_routes();
      route.set_dest_min(entry.dest_min);
      route.set_dest_max(entry.dest_max);
      route.set_next_hop(entry.next.node);
      route.set_link(entry.next.link);
      route.set_source(route::to_string(entry.next.source));
      if (entry.last_confirmed) route.set_last_confirmed(*entry.last_confirmed);
      route.set_stale(entry.stale);
    }
    const route::ForwarderStats& s = forwarder.stats();
    response->set_custody_held(forwarder.held());
    response->set_custody_taken(s.custody_taken);
    response->set_custody_refused(s.custody_refused);
    response->set_custody_copies(s.custody_copies);
    response->set_delivered(s.delivered);
    response->set_duplicates(s.duplicates);
    response->set_hop_limit_dropped(s.hop_limit_dropped);
    response->set_expired_dropped(s.expired_dropped);
    response->set_malformed(s.malformed);
    response->set_overheard(s.overheard);
  });
  return grpc::Status::OK;
}

}  // namespace acomms::service
