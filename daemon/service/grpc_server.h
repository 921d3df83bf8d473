#pragma once
// The gRPC endpoint: a unix socket (mode 0660) always, TCP only when
// configured, plus the standard health service and server reflection so that
// generic tools (grpcurl, grpc_health_probe) work without our .proto files.
// TCP is TLS (optionally mutual) unless the config asked for plaintext
// (grpc.insecure_tcp, which the config loader refuses to assume).
//
// Threads: built, switched (set_serving), reloaded and shut down from one
// thread (the daemon's main thread); the services run on gRPC's threads, which
// read the TLS certificates under TlsCertificates' own lock.

#include <grpcpp/grpcpp.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "service/tls_certificates.h"

namespace acomms::service {

struct Endpoints {
  std::string unix_socket;           // path
  std::string tcp_listen;            // "host:port" or empty
  std::optional<v1::TlsConfig> tls;  // for tcp_listen; none: plaintext
};

Endpoints endpoints_of(const v1::GrpcConfig& grpc);

class GrpcServer {
 public:
  // Binds and starts serving `services`. Throws std::runtime_error naming the
  // address that could not be bound (for example, another daemon holds the
  // socket), or the TLS file that cannot be used and why.
  GrpcServer(const Endpoints& endpoints, const std::vector<grpc::Service*>& services);
  ~GrpcServer();

  // Health for "" and every service: SERVING or NOT_SERVING.
  void set_serving(bool serving);
  // Stops accepting calls, gives in-flight calls `grace` to finish, then
  // cancels the rest; removes the socket file.
  void shutdown(std::chrono::milliseconds grace);

  // Re-reads the TLS files (SIGHUP) and logs the outcome: new connections
  // get the new certificates, or, if a file is bad, the error naming it and
  // the old certificates stay. Without TLS, logs that there is nothing to do.
  void reload_tls();

 private:
  std::string unix_socket_;
  // Declared before server_: gRPC calls into it until the server is gone.
  std::unique_ptr<TlsCertificates> tls_;
  std::vector<std::string> service_names_;
  std::unique_ptr<grpc::Server> server_;
};

}  // namespace acomms::service
