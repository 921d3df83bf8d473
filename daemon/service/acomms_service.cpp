#include "service/acomms_service.h"

namespace acomms::service {

AcommsService::AcommsService(DaemonIdentity identity, Node node)
    : identity_(std::move(identity)), node_(node), started_(std::chrono::steady_clock::now()) {}

grpc::Status AcommsService::GetStatus(grpc::ServerContext*, const v1::GetStatusRequest*,
                                      v1::Status* response) {
  response->set_version(identity_.version);
  response->set_uptime_s(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count());
  response->set_data_dir(identity_.data_dir);
  response->set_schema_version(static_cast<int32_t>(identity_.schema_version));
  response->set_driver(identity_.driver);
  response->set_mac(identity_.mac);
  response->set_modem_id(identity_.modem_id);
  auto stable = node_.submitter.types_stable();
  response->set_dccl_types(static_cast<int32_t>(node_.codec.types().size()));
  return grpc::Status::OK;
}

}  // namespace acomms::service
