#pragma once
// acomms.v1.Acomms: the control API. Each call is thin: validate, hand the
// work to the core thread (which owns the queues and the link), translate
// the answer into a gRPC status a person can act on. The methods are
// implemented by concern: message_rpcs.cpp (Submit, Encode, Decode),
// definition_rpcs.cpp, queue_rpcs.cpp, link_rpcs.cpp, event_rpcs.cpp,
// subscribe_rpc.cpp.

#include <chrono>
#include <shared_mutex>
#include <string>

#include "acomms/v1/acomms.grpc.pb.h"
#include "core/event_loop.h"
#include "dccl/codec.h"
#include "link/driver_supervisor.h"
#include "link/link_controller.h"
#include "mac/mac.h"
#include "queue/event_log_reader.h"
#include "queue/queue_manager.h"
#include "service/definition_loader.h"
#include "service/message_json.h"
#include "service/subscriber_hub.h"

namespace acomms::service {

// Facts about the running daemon that GetStatus reports.
struct DaemonFacts {
  std::string version;
  std::string data_dir;
  int64_t schema_version = 0;
  std::string driver;
  std::string mac;
  uint32_t modem_id = 0;
};

// The link's parts, read and changed on the core thread only.
struct LinkParts {
  mac::Mac& mac;
  link::DriverSupervisor& driver;
  link::LinkController& controller;
};

// What the service works on. Everything must outlive it.
struct ServiceParts {
  dccl::Codec& codec;
  queue::QueueManager& queues;
  core::EventLoop& core;
  LinkParts link;
  DefinitionLoader& definitions;
  queue::EventLogReader& events;
  SubscriberHub& subscribers;
};

// Submit is a callback (reactor) method and the rest are synchronous: a
// Submit waits for the disk, and parking a gRPC thread per Submit on that
// wait cost more CPU in thread hand-offs than the Submit itself.
class AcommsService final : public v1::Acomms::WithCallbackMethod_Submit<v1::Acomms::Service> {
 public:
  AcommsService(DaemonFacts facts, ServiceParts parts);

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
  grpc::Status SetCycle(grpc::ServerContext*, const v1::SetCycleRequest*, v1::SetCycleResponse*) override;

  grpc::Status Events(grpc::ServerContext*, const v1::EventsRequest*, v1::EventsResponse*) override;

 private:
  // Parses a request's message (payload or JSON) into a new message of
  // `type`. Caller holds definitions_ (shared).
  grpc::Status parse_message(const std::string& type, const std::string* payload, const std::string* json,
                             std::unique_ptr<google::protobuf::Message>* out) const;
  // Submit up to the journal: checks, parses, encodes and hands the message
  // to the journal, whose commit completes `reactor`. Not OK: nothing was
  // journaled and the call is the caller's to finish.
  grpc::Status submit_to_journal(const v1::SubmitRequest& request, v1::SubmitResponse* response,
                                 grpc::ServerUnaryReactor* reactor);
  // On the core thread, once the message is durable: queues it and
  // finishes the call.
  void accept_submitted(queue::QueuedMessage queued, v1::SubmitResponse* response,
                        grpc::ServerUnaryReactor* reactor);

  DaemonFacts facts_;
  ServiceParts parts_;
  std::chrono::steady_clock::time_point started_;
  // The codec's types and the set of queues only grow, in LoadDefinitions,
  // which holds this exclusively; every call that encodes, decodes or looks
  // types up holds it shared. (The core thread's own codec use is safe
  // because LoadDefinitions runs the load on the core thread.)
  mutable std::shared_mutex definitions_;
  mutable JsonReader json_reader_;
};

}  // namespace acomms::service
