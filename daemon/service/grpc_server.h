#pragma once
// The gRPC endpoint: a unix socket (mode 0660) always, TCP only when
// configured, plus the standard health service and server reflection so that
// generic tools (grpcurl, grpc_health_probe) work without our .proto files.

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>
#include <vector>

namespace acomms::service {

struct Endpoints {
  std::string unix_socket;  // path
  std::string tcp_listen;   // "host:port" or empty
};

class GrpcServer {
 public:
  // Binds and starts serving `services`. Throws std::runtime_error naming the
  // address that could not be bound (for example, another daemon holds the
  // socket).
  GrpcServer(const Endpoints& endpoints, const std::vector<grpc::Service*>& services);
  ~GrpcServer();

  // Health for "" and every service: SERVING or NOT_SERVING.
  void set_serving(bool serving);
  // Stops accepting calls, gives in-flight calls `grace` to finish, then
  // cancels the rest; removes the socket file.
  void shutdown(std::chrono::milliseconds grace);

 private:
  std::string unix_socket_;
  std::vector<std::string> service_names_;
  std::unique_ptr<grpc::Server> server_;
};

}  // namespace acomms::service
