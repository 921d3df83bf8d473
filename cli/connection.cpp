#include "connection.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

namespace acomms::cli {

std::string default_socket() {
  const char* from_env = std::getenv("ACOMMSD_SOCKET");
  return from_env && *from_env ? from_env : "/run/acommsd/acommsd.sock";
}

std::string target_for(const std::string& endpoint) {
  if (endpoint.rfind("tcp:", 0) == 0) return endpoint.substr(4);
  return "unix:" + endpoint;
}

std::shared_ptr<grpc::Channel> connect(const std::string& endpoint, double timeout_s) {
  bool is_tcp = endpoint.rfind("tcp:", 0) == 0;
  if (!is_tcp) {
    // gRPC only says "failed to connect"; the file system says why.
    struct stat info {};
    if (::stat(endpoint.c_str(), &info) != 0) {
      throw std::runtime_error("cannot reach acommsd at " + endpoint +
                               ": no such socket (is acommsd running? see --socket)");
    }
    if (!S_ISSOCK(info.st_mode)) {
      throw std::runtime_error("cannot reach acommsd at " + endpoint + ": not a socket");
    }
    if (::access(endpoint.c_str(), W_OK) != 0) {
      throw std::runtime_error("cannot reach acommsd at " + endpoint +
                               ": permission denied (is this user in the daemon's group?)");
    }
  }
  auto channel = grpc::CreateChannel(target_for(endpoint), grpc::InsecureChannelCredentials());
  auto deadline = std::chrono::system_clock::now() +
                  std::chrono::milliseconds(static_cast<int64_t>(timeout_s * 1000));
  if (!channel->WaitForConnected(deadline)) {
    throw std::runtime_error("cannot reach acommsd at " + endpoint +
                             ": connection refused or timed out (is acommsd running?)");
  }
  return channel;
}

}  // namespace acomms::cli
