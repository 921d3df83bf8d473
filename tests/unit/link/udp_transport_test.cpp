#include "link/udp_transport.h"

#include <gtest/gtest.h>

#include "link/driver.h"
#include "test_io.h"

namespace acomms::link {
namespace {

using testing::free_udp_port;
using testing::run_until;

std::string local(unsigned short port) { return "127.0.0.1:" + std::to_string(port); }

TEST(UdpTransportTest, LoopbackDatagramsBothWays) {
  asio::io_context io;
  auto port_a = free_udp_port(), port_b = free_udp_port();
  UdpTransport a(io, local(port_a), {local(port_b)});
  UdpTransport b(io, local(port_b), {local(port_a)});
  std::vector<std::pair<std::string, std::string>> at_a, at_b;
  a.open([&](std::string_view d, const std::string& from) { at_a.emplace_back(d, from); });
  b.open([&](std::string_view d, const std::string& from) { at_b.emplace_back(d, from); });
  EXPECT_EQ(a.local_port(), port_a);

  EXPECT_EQ(a.send_to_peers("to b"), "");
  EXPECT_EQ(b.send_to_peers(std::string("\0binary\xff", 8)), "");
  ASSERT_TRUE(run_until(io, [&] { return at_a.size() == 1 && at_b.size() == 1; }));
  EXPECT_EQ(at_b[0].first, "to b");
  EXPECT_EQ(at_b[0].second, local(port_a));
  EXPECT_EQ(at_a[0].first, std::string("\0binary\xff", 8));
}

TEST(UdpTransportTest, PeerNotListeningIsNotAFailure) {
  asio::io_context io;
  auto port_a = free_udp_port(), nobody = free_udp_port();
  UdpTransport a(io, local(port_a), {local(nobody)});
  a.open([](std::string_view, const std::string&) {});
  for (int i = 0; i < 3; ++i) EXPECT_EQ(a.send_to_peers("anyone?"), "");
  run_until(io, [] { return false; }, std::chrono::milliseconds(50));  // ICMP errors arrive
  EXPECT_EQ(a.state(), TransportState::kOpen);
  EXPECT_EQ(a.send_to_peers("still"), "");
}

TEST(UdpTransportTest, AddressInUseThrowsDriverErrorNamingIt) {
  asio::io_context io;
  UdpTransport a(io, "127.0.0.1:0", {});
  a.open([](std::string_view, const std::string&) {});
  std::string taken = local(a.local_port());
  UdpTransport b(io, taken, {});
  try {
    b.open([](std::string_view, const std::string&) {});
    FAIL() << "bound a port in use";
  } catch (const DriverError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot bind " + taken), std::string::npos) << e.what();
  }
  EXPECT_EQ(b.state(), TransportState::kClosed);
  EXPECT_NE(b.send_to_peers("x"), "");
}

}  // namespace
}  // namespace acomms::link
