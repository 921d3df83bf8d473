// The fake_micromodem executable's parts on real loopback sockets and a
// real pseudo-terminal: the ports carry the modem's bytes both ways, the
// UDP bus joins two waters, the console arms faults. Real time is needed
// here (the ports are the thing under test); every wait is for an event,
// bounded, and the clocks run 100 times faster than the wall clock.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <unistd.h>

#include <asio/connect.hpp>
#include <asio/read_until.hpp>
#include <asio/streambuf.hpp>
#include <asio/write.hpp>

#include <chrono>
#include <map>
#include <string>

#include "fake_micromodem.h"
#include "fake_modem_host.h"
#include "fault_console.h"
#include "host_ports.h"
#include "micromodem/nmea/receive_sentences.h"
#include "scaled_scheduler.h"
#include "udp_water_bus.h"

namespace acomms::fake_micromodem {
namespace {

using namespace std::chrono_literals;

constexpr double kScale = 100;

FakeModemConfig at(int address, Position position) {
  FakeModemConfig config;
  config.address = address;
  config.position = position;
  return config;
}

// Runs `context` until `done()` or a wall-clock bound.
template <typename Done>
bool run_until(asio::io_context& context, Done done, std::chrono::milliseconds bound = 5000ms) {
  auto deadline = std::chrono::steady_clock::now() + bound;
  while (!done() && std::chrono::steady_clock::now() < deadline) {
    context.run_for(10ms);
    context.restart();
  }
  return done();
}

TEST(FakeMicroModemIoTest, TcpPortCarriesCommandsAndRepliesOnLoopback) {
  asio::io_context context;
  ScaledScheduler scheduler(context, kScale);
  Water water(scheduler, {});
  FakeMicroModem modem(water, at(4, {}));
  TcpPort port(context, modem, 0);
  modem.power_on();
  asio::ip::tcp::socket client(context);
  client.connect({asio::ip::make_address("127.0.0.1"), port.port()});
  ASSERT_TRUE(run_until(context, [&] { return true; }));
  asio::write(client, asio::buffer(std::string("$CCCFQ,SRC\r\n")));
  asio::streambuf reply;
  bool replied = false;
  asio::async_read_until(client, reply, "\r\n", [&](const std::error_code& e, size_t) { replied = !e; });
  ASSERT_TRUE(run_until(context, [&] { return replied; }));
  std::string line(asio::buffers_begin(reply.data()), asio::buffers_end(reply.data()));
  EXPECT_EQ(line.substr(0, line.find("\r\n") + 2), "$CACFG,SRC,4*36\r\n");
}

TEST(FakeMicroModemIoTest, PtyPortLooksLikeARawSerialLine) {
  asio::io_context context;
  ScaledScheduler scheduler(context, kScale);
  Water water(scheduler, {});
  FakeMicroModem modem(water, at(5, {}));
  PtyPort pty(context, modem);
  modem.power_on();
  ASSERT_EQ(pty.path().rfind("/dev/", 0), 0u) << pty.path();
  int fd = ::open(pty.path().c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
  ASSERT_GE(fd, 0);
  std::string command = "$CCCFQ,SRC\r\n";
  ASSERT_EQ(::write(fd, command.data(), command.size()), static_cast<ssize_t>(command.size()));
  std::string received;
  ASSERT_TRUE(run_until(context, [&] {
    char buffer[256];
    ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n > 0) received.append(buffer, static_cast<size_t>(n));
    return received.find("$CACFG,SRC,5") != std::string::npos;
  })) << received;
  EXPECT_NE(received.find("$CACFG,SRC,5*37\r\n"), std::string::npos) << "no CR/LF translation";
  ::close(fd);
}

TEST(FakeMicroModemIoTest, UdpBusCarriesATransmissionToAnotherWaterAfterTravelTime) {
  asio::io_context context;
  ScaledScheduler scheduler(context, kScale);
  Water here(scheduler, {}), there(scheduler, {});
  UdpWaterBus bus_here(context, here, 0, {}), bus_there(context, there, 0, {});
  bus_here.add_peer(bus_there.port());
  bus_there.add_peer(bus_here.port());
  FakeMicroModem a(here, at(1, {0, 0, 0})), b(there, at(2, {1500, 0, 0}));
  FakeModemHost host_a(a, scheduler.clock()), host_b(b, scheduler.clock());
  a.power_on();
  b.power_on();
  host_a.send(to_sentence(micromodem::Cycle{0, 1, 2, 1, true, 1}, micromodem::Talker::kHost));
  ASSERT_TRUE(run_until(context, [&] { return host_a.count("CADRQ") == 1; }));
  host_a.send(to_sentence(micromodem::TransmitData{1, 2, true, "bus"}));
  ASSERT_TRUE(run_until(context, [&] { return host_a.count("CAACK") == 1; }));
  const HeardLine* rxd = host_b.first("CARXD");
  ASSERT_TRUE(rxd);
  EXPECT_EQ(micromodem::parse_received_data(rxd->sentence)->data, "bus");
  auto travel = host_b.first("CARXP")->at - host_a.first("CATXP")->at;
  EXPECT_GE(travel, 1s);
  EXPECT_LT(travel, 1s + 500ms) << "loopback latency stays small at scale " << kScale;
}

TEST(FaultConsoleTest, CommandsReachTheNamedModemAndMistakesAreExplained) {
  core::SimulatedScheduler scheduler(core::Clock::time_point{} + 1000h);
  Water water(scheduler, {});
  FakeMicroModem modem(water, at(2, {}));
  FakeModemHost host(modem, scheduler.clock());
  modem.power_on();
  scheduler.run_for(2s);
  host.clear();
  std::map<int, FakeMicroModem*> modems{{2, &modem}};
  EXPECT_EQ(run_fault_command("2 reset", modems), "ok");
  EXPECT_EQ(run_fault_command("2 error NMEA 7 injected by hand", modems), "ok");
  EXPECT_EQ(run_fault_command("2 checksum 1", modems), "ok");
  EXPECT_EQ(run_fault_command("2 unknown", modems), "ok");
  scheduler.run_for(2s);
  ASSERT_TRUE(host.first("CAREV"));
  EXPECT_EQ(host.first("CAREV")->sentence.field(2), "INIT");
  EXPECT_EQ(micromodem::parse_modem_error(host.first("CAERR")->sentence)->message, "injected by hand");
  // INIT and the error came at once; the unknown sentence is written raw,
  // so the armed checksum fault hits the next line: the AUV revision.
  ASSERT_EQ(host.refused().size(), 1u);
  EXPECT_EQ(host.refused()[0].kind, micromodem::ErrorKind::kBadChecksum);
  EXPECT_EQ(host.addresses(), (std::vector<std::string>{"CAREV", "CAERR", "CAZZZ", "CAREV"}));
  EXPECT_EQ(run_fault_command("3 reset", modems), "no fake modem with address 3");
  EXPECT_EQ(run_fault_command("2 silent maybe", modems), "usage: <address> silent on|off");
  EXPECT_EQ(run_fault_command("reset", modems), "usage: <address> <command> [arguments]");
  EXPECT_EQ(run_fault_command("2 checksum -1", modems), "unknown or incomplete command '2 checksum -1'");
}

}  // namespace
}  // namespace acomms::fake_micromodem
