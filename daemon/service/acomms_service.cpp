#include "service/acomms_service.h"

namespace acomms::service {

AcommsService::AcommsService(DaemonFacts facts, ServiceParts parts)
    : facts_(std::move(facts)), parts_(parts), started_(std::chrono::steady_clock::now()) {}

grpc::Status AcommsService::GetStatus(grpc::ServerContext*, const v1::GetStatusRequest*,
                                      v1::Status* response) {
  response->set_version(facts_.version);
  response->set_uptime_s(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count());
  response->set_data_dir(facts_.data_dir);
  response->set_schema_version(static_cast<int32_t>(facts_.schema_version));
  response->set_driver(facts_.driver);
  response->set_mac(facts_.mac);
  response->set_modem_id(facts_.modem_id);
  auto stable = parts_.submitter.types_stable();
  response->set_dccl_types(static_cast<int32_t>(parts_.codec.types().size()));
  return grpc::Status::OK;
}

}  // namespace acomms::service
