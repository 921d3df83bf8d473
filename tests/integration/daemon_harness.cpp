#include "daemon_harness.h"

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "grpc/health/v1/health.grpc.pb.h"

namespace acomms::testing {

bool wait_serving(ChildProcess& daemon, const std::string& socket, std::chrono::milliseconds timeout) {
  bool exited = false;
  auto serving = [&] {
    if (!daemon.running()) return exited = true;
    if (!std::filesystem::exists(socket)) return false;
    auto channel = grpc::CreateChannel("unix:" + socket, grpc::InsecureChannelCredentials());
    auto health = grpc::health::v1::Health::NewStub(channel);
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(1));
    grpc::health::v1::HealthCheckResponse response;
    grpc::Status status = health->Check(&context, {}, &response);
    return status.ok() && response.status() == grpc::health::v1::HealthCheckResponse::SERVING;
  };
  return wait_until(serving, timeout, std::chrono::milliseconds(50)) && !exited;
}

std::set<uint64_t> unix_connections(const std::string& socket) {
  // Lines: "Num RefCount Protocol Flags Type St Inode Path"; St 03 is connected.
  std::set<uint64_t> inodes;
  std::ifstream table("/proc/net/unix");
  std::string line;
  std::getline(table, line);  // the heading
  while (std::getline(table, line)) {
    std::istringstream fields(line);
    std::string num, refcount, protocol, flags, type, state, path;
    uint64_t inode = 0;
    if (!(fields >> num >> refcount >> protocol >> flags >> type >> state >> inode >> path)) continue;
    if (state == "03" && path == socket) inodes.insert(inode);
  }
  return inodes;
}

bool wait_connected(ChildProcess& client, const std::string& socket, const std::set<uint64_t>& before,
                    std::chrono::milliseconds timeout) {
  bool exited = false;
  auto connected = [&] {
    if (!client.running()) return exited = true;
    for (uint64_t inode : unix_connections(socket)) {
      if (before.count(inode) == 0) return true;
    }
    return false;
  };
  return wait_until(connected, timeout) && !exited;
}

std::unique_ptr<v1::Acomms::Stub> api(const std::string& socket) {
  return v1::Acomms::NewStub(grpc::CreateChannel("unix:" + socket, grpc::InsecureChannelCredentials()));
}

namespace {

int free_loopback_port(int type) {
  int fd = ::socket(AF_INET, type, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr));
  socklen_t length = sizeof(addr);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &length);
  ::close(fd);
  return ntohs(addr.sin_port);
}

}  // namespace

int free_udp_port() { return free_loopback_port(SOCK_DGRAM); }

int free_tcp_port() { return free_loopback_port(SOCK_STREAM); }

int bound_udp_socket(int port) {
  int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = htons(static_cast<uint16_t>(port));
  EXPECT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
  return fd;
}

}  // namespace acomms::testing
