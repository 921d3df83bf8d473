#include "service/acomms_service.h"

namespace acomms::service {

AcommsService::AcommsService(DaemonIdentity identity, Node node, const ApiRoles& roles)
    : identity_(std::move(identity)), node_(node), roles_(roles), started_(std::chrono::steady_clock::now()) {}

grpc::Status AcommsService::allowed(const grpc::ServerContextBase& context, std::string_view rpc) const {
  return roles_.check(context, "/acomms.v1.Acomms/" + std::string(rpc));
}

grpc::Status AcommsService::GetStatus(grpc::ServerContext* context, const v1::GetStatusRequest*,
                                      v1::Status* response) {
  if (grpc::Status denied = allowed(*context, "GetStatus"); !denied.ok()) return denied;
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
  if (std::optional<Role> role = roles_.role_of(*context)) response->set_caller_role(std::string(to_string(*role)));
  response->set_caller(ApiRoles::source(*context));
  if (node_.consistency_status) node_.core.call([&] { node_.consistency_status(response); });
  return grpc::Status::OK;
}

}  // namespace acomms::service
