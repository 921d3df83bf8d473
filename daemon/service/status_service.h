#pragma once
// acomms.v1.Acomms: the control API. For now it answers GetStatus; later
// calls (Submit, Subscribe, queues, link) are added beside it, each thin:
// validate, post to the core, translate the answer.

#include <chrono>
#include <string>

#include "acomms/v1/acomms.grpc.pb.h"

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
  explicit AcommsService(DaemonFacts facts);

  grpc::Status GetStatus(grpc::ServerContext* context, const v1::GetStatusRequest* request,
                         v1::Status* response) override;

 private:
  DaemonFacts facts_;
  std::chrono::steady_clock::time_point started_;
};

}  // namespace acomms::service
