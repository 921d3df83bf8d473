// The sd_notify datagram protocol, against a socket of our own.

#include "core/systemd_notify.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <string>

namespace acomms::core {
namespace {

class NotifySocket {
 public:
  explicit NotifySocket(const std::string& name) {
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    // Abstract namespace: no file to clean up.
    std::memcpy(addr.sun_path + 1, name.data(), name.size());
    EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&addr),
                     offsetof(sockaddr_un, sun_path) + 1 + name.size()),
              0);
  }
  ~NotifySocket() { ::close(fd_); }
  std::string receive() {
    char buffer[256];
    ssize_t n = ::recv(fd_, buffer, sizeof(buffer), MSG_DONTWAIT);
    return n > 0 ? std::string(buffer, n) : std::string();
  }

 private:
  int fd_;
};

TEST(SystemdNotify, SendsStateToAbstractSocket) {
  std::string name = "acomms-notify-test-" + std::to_string(::getpid());
  NotifySocket socket(name);
  ::setenv("NOTIFY_SOCKET", ("@" + name).c_str(), 1);
  EXPECT_TRUE(systemd_notify("READY=1"));
  EXPECT_EQ(socket.receive(), "READY=1");
  ::unsetenv("NOTIFY_SOCKET");
}

TEST(SystemdNotify, WithoutNotifySocketIsANoOp) {
  ::unsetenv("NOTIFY_SOCKET");
  EXPECT_TRUE(systemd_notify("READY=1"));
}

TEST(SystemdNotify, UnreachableSocketReportsFailure) {
  ::setenv("NOTIFY_SOCKET", "/nonexistent/notify.sock", 1);
  EXPECT_FALSE(systemd_notify("READY=1"));
  ::unsetenv("NOTIFY_SOCKET");
}

}  // namespace
}  // namespace acomms::core
