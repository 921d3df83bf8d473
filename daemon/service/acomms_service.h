#pragma once
// acomms.v1.Acomms: the control API. Each call is thin: validate, hand the
// work to the core thread (which owns the queues), translate the answer
// into a gRPC status a person can act on.

#include <chrono>
#include <string>

#include "acomms/v1/acomms.grpc.pb.h"
#include "core/event_loop.h"
#include "dccl/codec.h"
#include "queue/queue_manager.h"

namespace acomms::service {

// Facts about the running daemon that GetStatus reports.
struct DaemonFacts {
  std::string version;
  std::string data_dir;
  int64_t schema_version = 0;
  std::string driver;
  std::string mac;
  uint32_t modem_id = 0;
  int32_t dccl_types = 0;
};

class AcommsService final : public v1::Acomms::Service {
 public:
  // `codec`, `queues` and `core` must outlive the service; the queues are
  // only touched on the core thread (or through their thread-safe
  // journal_new).
  AcommsService(DaemonFacts facts, const dccl::Codec& codec, queue::QueueManager& queues,
                core::EventLoop& core);

  grpc::Status GetStatus(grpc::ServerContext* context, const v1::GetStatusRequest* request,
                         v1::Status* response) override;
  grpc::Status Submit(grpc::ServerContext* context, const v1::SubmitRequest* request,
                      v1::SubmitResponse* response) override;

 private:
  DaemonFacts facts_;
  const dccl::Codec& codec_;
  queue::QueueManager& queues_;
  core::EventLoop& core_;
  std::chrono::steady_clock::time_point started_;
};

}  // namespace acomms::service
