#pragma once
// Who may call what on the API: roles.
//
// Problem: any client with a valid certificate (or access to the unix
// socket) could do everything, flushing queues and commanding vehicles
// included. Decision: three roles, each a superset of the one before:
//   viewer    reads: status, types, subscribe, events, queues, link, track,
//             encode/decode, the acoustic environment and the model pool
//   operator  also acts on the water: submit, cancel, navigation input,
//             model requests, environment updates
//   admin     also changes the node: definitions, flush, the MAC cycle,
//             driver-specific transmissions
// A client's role comes from its certificate's subject common name (mutual
// TLS, config auth.client), else auth.default_tls_role; unix-socket and
// plaintext-TCP clients have auth.unix_socket_role (default admin, as
// before roles). The table of method -> role is here and only here
// (kRequiredRoles); every method checks it first thing (check()), and a
// test asserts that every method of both services is in the table.
//
// Thread-safe: built once, then only read (from gRPC's threads).

#include <grpcpp/grpcpp.h>

#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "acomms/v1/config.pb.h"

namespace acomms::service {

enum class Role { kViewer = 1, kOperator = 2, kAdmin = 3 };
std::string_view to_string(Role role);
std::optional<Role> role_named(std::string_view name);

// Full method name ("/acomms.v1.Acomms/Submit") -> the least role that may
// call it.
const std::map<std::string, Role, std::less<>>& required_roles();

class ApiRoles {
 public:
  // Throws std::invalid_argument naming the field for a role that is not
  // viewer, operator or admin, or a certificate name listed twice.
  explicit ApiRoles(const v1::AuthConfig& config);

  // The caller's role; nullopt for a TLS client whose certificate has no
  // role (refused everything).
  std::optional<Role> role_of(const grpc::ServerContextBase& context) const;
  // "role operator (certificate CN=ops)": for refusals.
  std::string describe(const grpc::ServerContextBase& context) const;
  // Where the role came from: "certificate CN=ops", "unix socket", "TLS
  // without a client certificate".
  static std::string source(const grpc::ServerContextBase& context);

  // OK when the caller's role may call `method` (a full method name from
  // required_roles()); otherwise PERMISSION_DENIED naming the role needed
  // and the caller's.
  grpc::Status check(const grpc::ServerContextBase& context, std::string_view method) const;

 private:
  std::map<std::string, Role> by_common_name_;
  std::optional<Role> default_tls_;
  Role unix_socket_;
};

}  // namespace acomms::service
