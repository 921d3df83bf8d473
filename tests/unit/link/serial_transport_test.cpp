#include "link/serial_transport.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <pty.h>  // openpty: in libc itself since glibc 2.34 (no libutil)
#include <unistd.h>

#include <vector>

#include "test_io.h"

namespace acomms::link {
namespace {

using testing::run_until;

// A pseudo-terminal pair stands in for a modem on a serial port: the
// transport opens the slave by name, the test plays the modem on the master.
struct Pty {
  Pty() {
    char name[128];
    if (openpty(&master, &slave, name, nullptr, nullptr) != 0) return;
    path = name;
    fcntl(master, F_SETFL, fcntl(master, F_GETFL) | O_NONBLOCK);
  }
  ~Pty() {
    close_master();
    if (slave >= 0) ::close(slave);
  }
  void close_master() {
    if (master >= 0) ::close(master);
    master = -1;
  }
  std::string read_master() {
    char buffer[256];
    ssize_t n = ::read(master, buffer, sizeof buffer);
    return n > 0 ? std::string(buffer, static_cast<size_t>(n)) : std::string();
  }
  int master = -1, slave = -1;
  std::string path;
};

TEST(SerialTransportTest, ExchangesBytesWithTheDevice) {
  Pty pty;
  ASSERT_FALSE(pty.path.empty()) << "openpty failed";
  asio::io_context io;
  SerialTransport transport(io, SerialSettings{pty.path, 19200}, RetryOptions{0.02, 0.1});
  std::string received;
  transport.open([&](std::string_view bytes) { received += bytes; }, nullptr);
  ASSERT_EQ(transport.state(), TransportState::kOpen);

  ASSERT_EQ(::write(pty.master, "$CAREV,1\r\n", 10), 10);
  ASSERT_TRUE(run_until(io, [&] { return received == "$CAREV,1\r\n"; }));

  ASSERT_TRUE(transport.write("$CCCFQ,ALL\r\n"));
  std::string from_transport;
  ASSERT_TRUE(run_until(io, [&] {
    from_transport += pty.read_master();
    return from_transport == "$CCCFQ,ALL\r\n";
  }));
}

TEST(SerialTransportTest, DeviceGoingAwayIsReportedAndRetried) {
  Pty pty;
  ASSERT_FALSE(pty.path.empty()) << "openpty failed";
  ::close(pty.slave);  // only the transport holds the slave now
  pty.slave = -1;
  asio::io_context io;
  SerialTransport transport(io, SerialSettings{pty.path, 9600}, RetryOptions{0.02, 0.05});
  std::vector<std::string> details;
  transport.open([](std::string_view) {},
                 [&](TransportState state, const std::string& detail) {
                   if (state == TransportState::kWaiting) details.push_back(detail);
                 });
  ASSERT_EQ(transport.state(), TransportState::kOpen);

  pty.close_master();  // the "modem" is unplugged: the slave reads EIO
  ASSERT_TRUE(run_until(io, [&] { return details.size() >= 3; }));
  EXPECT_NE(details[0].find(pty.path), std::string::npos) << details[0];
  EXPECT_NE(details[0].find("read failed"), std::string::npos) << details[0];
  EXPECT_NE(details[2].find("retrying in"), std::string::npos) << details[2];
}

TEST(SerialTransportTest, MissingDeviceIsRetriedWithTheDeviceNamed) {
  asio::io_context io;
  SerialTransport transport(io, SerialSettings{"/dev/ttyACOMMS-does-not-exist"}, RetryOptions{0.01, 0.02});
  std::vector<std::string> details;
  transport.open([](std::string_view) {},
                 [&](TransportState state, const std::string& detail) {
                   if (state == TransportState::kWaiting) details.push_back(detail);
                 });
  EXPECT_EQ(transport.state(), TransportState::kWaiting);
  ASSERT_TRUE(run_until(io, [&] { return details.size() >= 3; }));
  EXPECT_NE(details[0].find("/dev/ttyACOMMS-does-not-exist: cannot open"), std::string::npos) << details[0];
  EXPECT_FALSE(transport.write("x"));
}

}  // namespace
}  // namespace acomms::link
