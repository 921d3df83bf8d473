#include "service/api_roles.h"

#include <stdexcept>

namespace acomms::service {
namespace {

constexpr std::string_view kAcomms = "/acomms.v1.Acomms/";
constexpr std::string_view kGram = "/acomms.v1.Gram/";

std::string method(std::string_view service, std::string_view name) { return std::string(service) + std::string(name); }

// The client certificate's subject common name, if the call came over
// mutual TLS.
std::optional<std::string> common_name(const grpc::ServerContextBase& context) {
  std::shared_ptr<const grpc::AuthContext> auth = context.auth_context();
  if (!auth) return std::nullopt;
  std::vector<grpc::string_ref> names = auth->FindPropertyValues("x509_common_name");
  if (names.empty()) return std::nullopt;
  return std::string(names.front().data(), names.front().size());
}

bool over_tls(const grpc::ServerContextBase& context) {
  std::shared_ptr<const grpc::AuthContext> auth = context.auth_context();
  if (!auth) return false;
  std::vector<grpc::string_ref> kind = auth->FindPropertyValues("transport_security_type");
  return !kind.empty() && std::string_view(kind.front().data(), kind.front().size()) == "ssl";
}

}  // namespace

std::string_view to_string(Role role) {
  switch (role) {
    case Role::kViewer: return "viewer";
    case Role::kOperator: return "operator";
    case Role::kAdmin: return "admin";
  }
  return "?";
}

std::optional<Role> role_named(std::string_view name) {
  if (name == "viewer") return Role::kViewer;
  if (name == "operator") return Role::kOperator;
  if (name == "admin") return Role::kAdmin;
  return std::nullopt;
}

const std::map<std::string, Role, std::less<>>& required_roles() {
  static const std::map<std::string, Role, std::less<>> table = {
      {method(kAcomms, "GetStatus"), Role::kViewer},
      {method(kAcomms, "ListTypes"), Role::kViewer},
      {method(kAcomms, "Subscribe"), Role::kViewer},
      {method(kAcomms, "ListQueued"), Role::kViewer},
      {method(kAcomms, "QueueStats"), Role::kViewer},
      {method(kAcomms, "LinkStatus"), Role::kViewer},
      {method(kAcomms, "Events"), Role::kViewer},
      {method(kAcomms, "Encode"), Role::kViewer},
      {method(kAcomms, "Decode"), Role::kViewer},
      {method(kAcomms, "Track"), Role::kViewer},
      {method(kAcomms, "ListRoutes"), Role::kViewer},
      {method(kAcomms, "Submit"), Role::kOperator},
      {method(kAcomms, "Cancel"), Role::kOperator},
      {method(kAcomms, "SubmitNavigation"), Role::kOperator},
      {method(kAcomms, "LoadDefinitions"), Role::kAdmin},
      {method(kAcomms, "Flush"), Role::kAdmin},
      {method(kAcomms, "SetCycle"), Role::kAdmin},
      {method(kAcomms, "SetLinkEnabled"), Role::kAdmin},
      {method(kAcomms, "DriverSpecific"), Role::kAdmin},
      {method(kGram, "GetEnvironment"), Role::kViewer},
      {method(kGram, "PoolStatus"), Role::kViewer},
      // Model runs take the pool's CPU: for those who steer the vehicle.
      {method(kGram, "TransmissionLoss"), Role::kOperator},
      {method(kGram, "Arrivals"), Role::kOperator},
      {method(kGram, "DepthObjective"), Role::kOperator},
      {method(kGram, "UpdateEnvironment"), Role::kOperator},
  };
  return table;
}

ApiRoles::ApiRoles(const v1::AuthConfig& config) {
  auto parse = [](const std::string& field, const std::string& name) {
    std::optional<Role> role = role_named(name);
    if (!role) throw std::invalid_argument(field + " \"" + name + "\" is not a role (viewer, operator or admin)");
    return *role;
  };
  for (const v1::ClientRole& client : config.client()) {
    if (client.common_name().empty()) throw std::invalid_argument("auth.client: common_name is empty");
    Role role = parse("auth.client " + client.common_name() + ": role", client.role());
    if (!by_common_name_.emplace(client.common_name(), role).second) {
      throw std::invalid_argument("auth.client " + client.common_name() + " is listed twice");
    }
  }
  if (!config.default_tls_role().empty()) {
    default_tls_ = parse("auth.default_tls_role", config.default_tls_role());
  } else if (by_common_name_.empty()) {
    default_tls_ = Role::kAdmin;  // no roles configured: everything, as before roles
  }
  unix_socket_ = config.unix_socket_role().empty() ? Role::kAdmin
                                                   : parse("auth.unix_socket_role", config.unix_socket_role());
}

std::optional<Role> ApiRoles::role_of(const grpc::ServerContextBase& context) const {
  if (std::optional<std::string> name = common_name(context)) {
    auto it = by_common_name_.find(*name);
    return it != by_common_name_.end() ? std::optional<Role>(it->second) : default_tls_;
  }
  if (over_tls(context)) return default_tls_;
  return unix_socket_;
}

std::string ApiRoles::source(const grpc::ServerContextBase& context) {
  if (std::optional<std::string> name = common_name(context)) return "certificate CN=" + *name;
  return over_tls(context) ? "TLS without a client certificate" : "unix socket";
}

std::string ApiRoles::describe(const grpc::ServerContextBase& context) const {
  std::optional<Role> role = role_of(context);
  return (role ? "role " + std::string(to_string(*role)) : std::string("no role")) + " (" + source(context) + ")";
}

grpc::Status ApiRoles::check(const grpc::ServerContextBase& context, std::string_view method) const {
  auto it = required_roles().find(method);
  // Not in the table: refused, never allowed by omission (the table's
  // test keeps this from happening).
  if (it == required_roles().end()) {
    return grpc::Status(grpc::StatusCode::PERMISSION_DENIED, std::string(method) + " has no role: refused");
  }
  std::optional<Role> role = role_of(context);
  if (role && *role >= it->second) return grpc::Status::OK;
  std::string name(method.substr(method.rfind('/') + 1));
  return grpc::Status(grpc::StatusCode::PERMISSION_DENIED,
                      name + " needs role " + std::string(to_string(it->second)) + " or higher; this client has " +
                          describe(context) + " (config auth.client / auth.unix_socket_role)");
}

}  // namespace acomms::service
