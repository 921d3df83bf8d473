#include "service/grpc_server.h"

#include <absl/synchronization/mutex.h>
#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "acomms/v1/acomms.grpc.pb.h"
#include "acomms/v1/gram.grpc.pb.h"
#include "service/tls_refusal_log.h"
#include "core/pem_files.h"

namespace acomms::service {
namespace {

// A socket file left by a daemon that died is removed; one that a live
// daemon answers on is not ours to take.
void clear_stale_socket(const std::string& path) {
  struct stat info {};
  if (::lstat(path.c_str(), &info) != 0) return;
  if (!S_ISSOCK(info.st_mode)) {
    throw std::runtime_error("unix socket " + path + ": a file that is not a socket is in the way");
  }
  int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, path.c_str(), sizeof(addr.sun_path) - 1);
  bool live = ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0;
  ::close(fd);
  if (live) throw std::runtime_error("unix socket " + path + " is in use by another process");
  ::unlink(path.c_str());
}

std::shared_ptr<grpc::ServerCredentials> tcp_credentials(const Endpoints& endpoints,
                                                        std::unique_ptr<TlsCertificates>& tls) {
  if (!endpoints.tls) {
    spdlog::warn(
        "grpc: TCP {} is plaintext with no authentication (grpc.insecure_tcp: true): anyone who "
        "can reach it can submit, cancel and flush; configure grpc.tls instead",
        endpoints.tcp_listen);
    return grpc::InsecureServerCredentials();
  }
  try {
    tls = std::make_unique<TlsCertificates>(*endpoints.tls);
  } catch (const core::PemFileError& e) {
    throw std::runtime_error(std::string("cannot serve TLS on ") + endpoints.tcp_listen + ": " + e.what());
  }
  log_tls_refusals(*endpoints.tls);
  return tls->credentials();
}

}  // namespace

Endpoints endpoints_of(const v1::GrpcConfig& grpc) {
  Endpoints endpoints{grpc.unix_socket(), grpc.tcp_listen(), std::nullopt};
  if (grpc.has_tls()) endpoints.tls = grpc.tls();
  return endpoints;
}

GrpcServer::GrpcServer(const Endpoints& endpoints, const std::vector<grpc::Service*>& services)
    : unix_socket_(endpoints.unix_socket) {
  // Debian's abseil is built without NDEBUG, so absl::Mutex (which gRPC
  // locks many times per call) keeps its debugging lock-order graph up to
  // date on every lock, as release builds of abseil do not. Turned off, 8
  // clients submit about 6% faster; it only ever reported lock-order
  // cycles, for abseil's own debugging.
  absl::SetMutexDeadlockDetectionMode(absl::OnDeadlockCycle::kIgnore);
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();

  std::filesystem::path socket_dir = std::filesystem::path(unix_socket_).parent_path();
  if (!socket_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(socket_dir, ec);
    if (ec) throw std::runtime_error("unix socket dir " + socket_dir.string() + ": " + ec.message());
  }
  clear_stale_socket(unix_socket_);

  grpc::ServerBuilder builder;
  int unix_port = 0;
  builder.AddListeningPort("unix:" + unix_socket_, grpc::InsecureServerCredentials(), &unix_port);
  int tcp_port = 0;
  if (!endpoints.tcp_listen.empty()) {
    builder.AddListeningPort(endpoints.tcp_listen, tcp_credentials(endpoints, tls_), &tcp_port);
  }
  for (grpc::Service* service : services) builder.RegisterService(service);
  // The synchronous calls (all but Submit, a callback method that never
  // holds a thread) each take a thread while they run. With gRPC's default
  // of at most 2 idle pollers, each burst of concurrent calls creates and
  // destroys threads (thousands a second under load); a pool kept ready
  // avoids that.
  builder.SetSyncServerOption(grpc::ServerBuilder::SyncServerOption::MIN_POLLERS, 8);
  builder.SetSyncServerOption(grpc::ServerBuilder::SyncServerOption::MAX_POLLERS, 32);

  // The socket is created by bind(2) inside BuildAndStart; a umask makes it
  // 0660 from the first instant instead of briefly wider.
  mode_t old_mask = ::umask(0117);
  server_ = builder.BuildAndStart();
  ::umask(old_mask);
  if (!server_ || unix_port == 0) {
    throw std::runtime_error("cannot listen on unix:" + unix_socket_);
  }
  if (!endpoints.tcp_listen.empty() && tcp_port == 0) {
    server_->Shutdown();
    throw std::runtime_error("cannot listen on TCP " + endpoints.tcp_listen +
                             " (address in use, or not an address of this machine)");
  }
  ::chmod(unix_socket_.c_str(), 0660);

  service_names_ = {v1::Acomms::service_full_name(), v1::Gram::service_full_name()};
  std::string tcp;
  if (!endpoints.tcp_listen.empty()) {
    tcp = " and tcp " + endpoints.tcp_listen;
    if (tls_) {
      tcp += (tls_->mutual() ? " (mutual TLS, clients from " + endpoints.tls->client_ca_file() + "; "
                             : " (TLS; ") +
             "certificate " + tls_->description() + ")";
    } else {
      tcp += " (plaintext)";
    }
  }
  spdlog::info("grpc: listening on unix:{}{}", unix_socket_, tcp);
}

void GrpcServer::reload_tls() {
  if (!tls_) {
    spdlog::info("grpc: reload: no TLS certificates to re-read (grpc.tls is not set)");
    return;
  }
  try {
    tls_->reload();
    spdlog::info("grpc: reloaded TLS certificates for new connections: {}", tls_->description());
  } catch (const core::PemFileError& e) {
    spdlog::error("grpc: reload failed, still serving the previous TLS certificates: {}", e.what());
  }
}

GrpcServer::~GrpcServer() { shutdown(std::chrono::milliseconds(0)); }

void GrpcServer::set_serving(bool serving) {
  if (!server_) return;
  grpc::HealthCheckServiceInterface* health = server_->GetHealthCheckService();
  if (health == nullptr) return;
  health->SetServingStatus(serving);
  for (const auto& name : service_names_) health->SetServingStatus(name, serving);
}

void GrpcServer::shutdown(std::chrono::milliseconds grace) {
  if (!server_) return;
  set_serving(false);
  server_->Shutdown(std::chrono::system_clock::now() + grace);
  server_->Wait();
  server_.reset();
  ::unlink(unix_socket_.c_str());
}

}  // namespace acomms::service
