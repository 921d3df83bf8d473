// fake_micromodem's line commands (line_console.h) on a real loopback TCP
// port: unplugging ends the host's connection and refuses new ones,
// plugging serves again on the same port, noise-for writes bytes in chunks
// of the rate asked for, and stops; mistakes are explained. Real time (the
// port is the thing under test): every wait is for an event, bounded.

#include <gtest/gtest.h>

#include <asio/read.hpp>
#include <asio/read_until.hpp>
#include <asio/streambuf.hpp>
#include <asio/write.hpp>

#include <array>
#include <chrono>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "fake_micromodem.h"
#include "host_ports.h"
#include "line_console.h"
#include "scaled_scheduler.h"

namespace acomms::fake_micromodem {
namespace {

using namespace std::chrono_literals;

template <typename Done>
bool run_until(asio::io_context& context, Done done, std::chrono::milliseconds bound = 5000ms) {
  auto deadline = std::chrono::steady_clock::now() + bound;
  while (!done() && std::chrono::steady_clock::now() < deadline) {
    context.run_for(10ms);
    context.restart();
  }
  return done();
}

struct Rig {
  Rig() : scheduler(context, 1), water(scheduler, {}), modem(water, config()), port(context, modem, 0),
          console(context, {{3, &modem}}, {{3, &port}}) {
    modem.power_on();
  }
  static FakeModemConfig config() {
    FakeModemConfig c;
    c.address = 3;
    return c;
  }
  bool connect(asio::ip::tcp::socket& client) {
    std::error_code error;
    client.connect({asio::ip::make_address("127.0.0.1"), port.port()}, error);
    return !error;
  }
  asio::io_context context;
  ScaledScheduler scheduler;
  Water water;
  FakeMicroModem modem;
  TcpPort port;
  LineConsole console;
};

TEST(FakeLineConsoleTest, UnplugEndsTheConnectionAndRefusesNewOnesUntilPluggedBackOnTheSamePort) {
  Rig rig;
  uint16_t port = rig.port.port();
  asio::ip::tcp::socket client(rig.context);
  ASSERT_TRUE(rig.connect(client));
  ASSERT_TRUE(run_until(rig.context, [] { return true; }));
  EXPECT_EQ(rig.console.run("3 unplug"), std::optional<std::string>("ok"));
  // The host's read ends: the connection is gone.
  bool ended = false;
  std::array<char, 64> buffer{};
  client.async_read_some(asio::buffer(buffer), [&](const std::error_code& e, size_t) { ended = bool(e); });
  ASSERT_TRUE(run_until(rig.context, [&] { return ended; }));
  asio::ip::tcp::socket refused(rig.context);
  EXPECT_FALSE(rig.connect(refused)) << "nothing listens while unplugged";

  EXPECT_EQ(rig.console.run("3 plug"), std::optional<std::string>("ok"));
  EXPECT_EQ(rig.port.port(), port);
  asio::ip::tcp::socket again(rig.context);
  ASSERT_TRUE(rig.connect(again));
  ASSERT_TRUE(run_until(rig.context, [] { return true; }));
  asio::write(again, asio::buffer(std::string("$CCCFQ,SRC\r\n")));
  asio::streambuf reply;
  bool replied = false;
  asio::async_read_until(again, reply, "\r\n", [&](const std::error_code& e, size_t) { replied = !e; });
  ASSERT_TRUE(run_until(rig.context, [&] { return replied; }));
  std::string line(asio::buffers_begin(reply.data()), asio::buffers_end(reply.data()));
  EXPECT_EQ(line.substr(0, line.find("\r\n") + 2), "$CACFG,SRC,3*31\r\n") << "the modem behind it kept running";
}

TEST(FakeLineConsoleTest, NoiseForWritesChunksOfTheRateAskedForAndThenStops) {
  Rig rig;
  asio::ip::tcp::socket client(rig.context);
  ASSERT_TRUE(rig.connect(client));
  size_t received = 0;
  std::string boot_lines;
  bool noise_started = false;
  std::array<char, 4096> buffer{};
  std::function<void()> read = [&] {
    client.async_read_some(asio::buffer(buffer), [&](const std::error_code& e, size_t n) {
      if (e) return;
      if (!noise_started) boot_lines.append(buffer.data(), n);
      received += n;
      read();
    });
  };
  read();
  // The modem's own boot line ($CAREV,...,AUV) comes 1 s after power-on; on
  // a slow machine it once landed in the quiet window below and read as
  // noise that had not stopped. Let the boot finish first, then count noise.
  ASSERT_TRUE(run_until(rig.context, [&] { return boot_lines.find(",AUV,") != std::string::npos; }))
      << "the fake modem never finished booting: " << boot_lines;
  noise_started = true;
  received = 0;
  auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(rig.console.run("3 noise-for 0.5 20000"), std::optional<std::string>("ok"));
  // 0.5 s at 20000 bytes/s: chunks of 1000 bytes every 50 ms (fewer when
  // the machine is slow, never more than 11), the first at once; then quiet.
  run_until(rig.context, [&] { return std::chrono::steady_clock::now() - start > 1s; }, 2000ms);
  EXPECT_GE(received, 1000u);
  EXPECT_LE(received, 11000u);
  EXPECT_EQ(received % 1000, 0u) << "only whole noise chunks, nothing else from the modem";
  size_t at_end = received;
  auto later = std::chrono::steady_clock::now();
  run_until(rig.context, [&] { return std::chrono::steady_clock::now() - later > 300ms; }, 1000ms);
  EXPECT_EQ(received, at_end) << "the noise stopped";
}

TEST(FakeLineConsoleTest, OtherCommandsAreLeftToTheFaultConsoleAndMistakesAreExplained) {
  Rig rig;
  EXPECT_EQ(rig.console.run("3 reset"), std::nullopt);
  EXPECT_EQ(rig.console.run("nonsense"), std::nullopt);
  EXPECT_EQ(rig.console.run("4 unplug"), std::optional<std::string>("no fake modem on TCP with address 4"));
  EXPECT_EQ(rig.console.run("3 noise-for"), std::optional<std::string>("usage: <address> noise-for <seconds> [bytes/s]"));
  EXPECT_EQ(rig.console.run("3 noise-for 1 5"), std::optional<std::string>("noise-for: bytes/s must be in 20..10000000"));
}

}  // namespace
}  // namespace acomms::fake_micromodem
