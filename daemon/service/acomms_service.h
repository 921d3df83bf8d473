#pragma once
// acomms.v1.Acomms: the control API. Each call is thin: validate, hand the
// work to the core thread (which owns the queues and the link), translate
// the answer into a gRPC status a person can act on. The methods are
// implemented by concern: message_rpcs.cpp (Submit, Encode, Decode),
// definition_rpcs.cpp, queue_rpcs.cpp, link_rpcs.cpp, driver_specific_rpc.cpp,
// event_rpcs.cpp, subscribe_rpc.cpp, telemetry_rpcs.cpp.

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "acomms/v1/acomms.grpc.pb.h"
#include "core/event_loop.h"
#include "dccl/codec.h"
#include "dccl/message_json.h"
#include "link/driver_supervisor.h"
#include "link/link_controller.h"
#include "mac/mac.h"
#include "queue/event_log_reader.h"
#include "queue/queue_manager.h"
#include "queue/submitter.h"
#include "service/api_roles.h"
#include "service/definitions.h"
#include "service/subscriber_hub.h"
#include "telemetry/telemetry_node.h"
#include "telemetry/track_reader.h"

namespace acomms::route {
class Forwarder;  // route/forwarder.h (ListRoutes: route_rpcs.cpp)
}

namespace acomms::service {

// What this daemon is and runs with, fixed at start: what GetStatus reports
// about it.
struct DaemonIdentity {
  std::string version;
  std::string data_dir;
  int64_t schema_version = 0;
  std::string driver;
  std::string mac;
  uint32_t modem_id = 0;
};

// One of the node's links: the MAC that cycles the slots, the supervised
// modem driver, and the LinkController that binds them to the queues (what
// Goby calls a binding). Read and changed on the core thread only.
struct Link {
  std::string name;  // LinkConfig.name ("default" for the single-link form)
  std::string driver_name;  // driver.name
  std::string mac_name;     // mac.name
  double cost = 0;          // LinkConfig.cost
  mac::Mac& mac;
  link::DriverSupervisor& driver;
  link::LinkController& controller;
};

// The node the service operates on: its layers, each owned by the daemon
// and outliving the service.
struct Node {
  dccl::Codec& codec;
  queue::QueueManager& queues;
  // The way in for a client's message, and the lock that keeps the codec's
  // types and the set of queues stable while a call reads them.
  queue::Submitter& submitter;
  core::EventLoop& core;
  std::vector<Link> links;  // config order; at least one
  Definitions& definitions;  // LoadDefinitions' work (the node's)
  queue::EventLogReader& events;
  SubscriberHub& subscribers;
  // Position telemetry (core thread) and the received tracks (any thread).
  telemetry::TelemetryNode& telemetry;
  telemetry::TrackReader& track;
  // The gateway (config `routing`, core thread); null without.
  route::Forwarder* forwarder = nullptr;
  // The fleet consistency watch's status fields (node/consistency_watch.h),
  // GetStatus's and one link's (by index) in LinkStatus; core thread.
  // Unset: not reported.
  std::function<void(v1::Status*)> consistency_status;
  std::function<void(int link, v1::LinkStatusResponse*)> consistency_link_status;
};

// Submit is a callback (reactor) method and the rest are synchronous: a
// Submit waits for the disk, and parking a gRPC thread per Submit on that
// wait cost more CPU in thread hand-offs than the Submit itself.
class AcommsService final : public v1::Acomms::WithCallbackMethod_Submit<v1::Acomms::Service> {
 public:
  // `roles` (who may call what: api_roles.h) must outlive the service.
  AcommsService(DaemonIdentity identity, Node node, const ApiRoles& roles);

  grpc::Status GetStatus(grpc::ServerContext*, const v1::GetStatusRequest*, v1::Status*) override;

  grpc::Status LoadDefinitions(grpc::ServerContext*, const v1::LoadDefinitionsRequest*,
                               v1::LoadDefinitionsResponse*) override;
  grpc::Status ListTypes(grpc::ServerContext*, const v1::ListTypesRequest*, v1::ListTypesResponse*) override;

  grpc::ServerUnaryReactor* Submit(grpc::CallbackServerContext*, const v1::SubmitRequest*,
                                   v1::SubmitResponse*) override;
  grpc::Status Encode(grpc::ServerContext*, const v1::EncodeRequest*, v1::EncodeResponse*) override;
  grpc::Status Decode(grpc::ServerContext*, const v1::DecodeRequest*, v1::DecodeResponse*) override;

  grpc::Status Subscribe(grpc::ServerContext*, const v1::SubscribeRequest*,
                         grpc::ServerWriter<v1::ReceivedMessage>*) override;

  grpc::Status ListQueued(grpc::ServerContext*, const v1::ListQueuedRequest*, v1::ListQueuedResponse*) override;
  grpc::Status Cancel(grpc::ServerContext*, const v1::CancelRequest*, v1::CancelResponse*) override;
  grpc::Status Flush(grpc::ServerContext*, const v1::FlushRequest*, v1::FlushResponse*) override;
  grpc::Status QueueStats(grpc::ServerContext*, const v1::QueueStatsRequest*, v1::QueueStatsResponse*) override;

  grpc::Status LinkStatus(grpc::ServerContext*, const v1::LinkStatusRequest*, v1::LinkStatusResponse*) override;
  grpc::Status ListRoutes(grpc::ServerContext*, const v1::ListRoutesRequest*, v1::ListRoutesResponse*) override;
  grpc::Status SetCycle(grpc::ServerContext*, const v1::SetCycleRequest*, v1::SetCycleResponse*) override;
  grpc::Status SetLinkEnabled(grpc::ServerContext*, const v1::SetLinkEnabledRequest*,
                              v1::SetLinkEnabledResponse*) override;
  grpc::Status DriverSpecific(grpc::ServerContext*, const v1::DriverSpecificRequest*,
                              v1::DriverSpecificResponse*) override;

  grpc::Status Events(grpc::ServerContext*, const v1::EventsRequest*, v1::EventsResponse*) override;

  grpc::Status SubmitNavigation(grpc::ServerContext*, grpc::ServerReader<v1::NavigationFix>*,
                                v1::SubmitNavigationResponse*) override;
  grpc::Status Track(grpc::ServerContext*, const v1::TrackRequest*, v1::TrackResponse*) override;

 private:
  // Parses a request's message (payload or JSON) into a new message of
  // `type`. Caller holds types_stable().
  grpc::Status parse_message(const std::string& type, const std::string* payload, const std::string* json,
                             std::unique_ptr<google::protobuf::Message>* out) const;
  // The link named `name` ("": the first), or NOT_FOUND naming the links.
  grpc::Status find_link(const std::string& name, Link** out);
  // A Submit's ttl_s and message, parsed.
  grpc::Status parse_submitted(const v1::SubmitRequest& request,
                               std::unique_ptr<google::protobuf::Message>* out) const;
  // A stored telemetry position as Subscribe's replay sends it: as it was
  // published live.
  v1::ReceivedMessage from_track(const telemetry::ReceivedPosition& position) const;

  // The role check every method makes first: OK, or PERMISSION_DENIED
  // naming the role `rpc` (a method of acomms.v1.Acomms) needs.
  grpc::Status allowed(const grpc::ServerContextBase& context, std::string_view rpc) const;

  DaemonIdentity identity_;
  Node node_;
  const ApiRoles& roles_;
  std::chrono::steady_clock::time_point started_;
  mutable dccl::JsonReader json_reader_;
};

}  // namespace acomms::service
