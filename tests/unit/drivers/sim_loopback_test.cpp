// Two sim nodes in one test process exchanging envelopes over real loopback
// UDP, in real time on the AsioScheduler, as two daemons would. Bounded:
// 150 m apart (0.1 s) at rate 2 with one frame (1.324 s in the water).
#include <gtest/gtest.h>

#include <asio/ip/udp.hpp>

#include "core/scheduler.h"
#include "link/rate_table.h"
#include "sim/sim_driver.h"

namespace acomms::drivers {
namespace {

using core::Clock;
using v1::ModemTransmission;

unsigned short free_udp_port() {
  asio::io_context io;
  asio::ip::udp::socket socket(io, asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  return socket.local_endpoint().port();
}

bool run_until(asio::io_context& io, const std::function<bool()>& done, std::chrono::milliseconds timeout) {
  auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done() && std::chrono::steady_clock::now() < deadline) {
    if (io.stopped()) io.restart();
    io.run_one_for(std::chrono::milliseconds(10));
  }
  return done();
}

struct LoopbackNode {
  LoopbackNode(asio::io_context& io, core::Scheduler& scheduler, int id, double x, unsigned short port,
               unsigned short peer) {
    v1::DriverConfig config;
    config.set_name("sim");
    config.set_modem_id(id);
    config.mutable_sim()->mutable_position()->set_x(x);
    config.mutable_sim()->set_listen("127.0.0.1:" + std::to_string(port));
    config.mutable_sim()->add_peers("127.0.0.1:" + std::to_string(peer));
    driver = std::make_unique<SimDriver>(config, scheduler, &io);
    link::DriverCallbacks callbacks;
    callbacks.on_receive = [this, &scheduler](const ModemTransmission& tx) {
      received.push_back(tx);
      received_at.push_back(scheduler.clock().now());
    };
    callbacks.on_data_request = [](ModemTransmission* tx) { tx->add_frame(std::string("over loopback")); };
    callbacks.on_transmit_result = [this](const ModemTransmission&, bool ok, const std::string&) {
      results.push_back(ok);
    };
    callbacks.on_raw = [this](std::string_view, bool outgoing) { ++(outgoing ? raw_out : raw_in); };
    driver->start(callbacks);
  }
  std::unique_ptr<SimDriver> driver;
  std::vector<ModemTransmission> received;
  std::vector<Clock::time_point> received_at;
  std::vector<bool> results;
  int raw_in = 0, raw_out = 0;
};

TEST(SimLoopbackTest, TwoProcessesWorthOfNodesOverLoopbackUdp) {
  asio::io_context io;
  core::SystemClock clock;
  core::AsioScheduler scheduler(io, clock);
  auto port_a = free_udp_port(), port_b = free_udp_port();
  LoopbackNode a(io, scheduler, 1, 0, port_a, port_b), b(io, scheduler, 2, 150, port_b, port_a);
  ASSERT_EQ(b.driver->listen_port(), port_b);

  // Garbage on B's socket first: counted, logged, harmless.
  {
    asio::ip::udp::socket junk(io, asio::ip::udp::endpoint(asio::ip::udp::v4(), 0));
    junk.send_to(asio::buffer(std::string("not an envelope")),
                 asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), port_b));
  }
  ASSERT_TRUE(run_until(io, [&] { return b.driver->stats().garbage == 1; }, std::chrono::seconds(1)));

  ModemTransmission tx;
  tx.set_src(1);
  tx.set_dest(2);
  tx.set_rate(2);
  auto start = clock.now();
  a.driver->initiate_transmission(tx);
  // DATA arrives at 1.424 s; B's ACK leaves at 1.924 s and is back at 2.724 s.
  ASSERT_TRUE(run_until(io, [&] { return !a.received.empty(); }, std::chrono::seconds(5)));
  ASSERT_EQ(b.received.size(), 1u);
  EXPECT_EQ(b.received[0].frame(0), "over loopback");
  auto expected = std::chrono::milliseconds(100) + link::packet_air_time(*link::find_rate(2), 1);
  // Never early (that would mean a missing delay); late only by scheduling
  // jitter, which a loaded machine can stretch.
  auto late = b.received_at[0] - start - expected;
  EXPECT_GE(late, std::chrono::milliseconds(-5));
  EXPECT_LT(late, std::chrono::milliseconds(300));
  EXPECT_EQ(a.received[0].type(), ModemTransmission::ACK);
  EXPECT_EQ(a.received[0].acked_frame_size(), 1);
  EXPECT_EQ(a.results, std::vector<bool>{true});
  EXPECT_EQ(a.raw_out, 1);
  EXPECT_EQ(b.raw_in, 2);  // the junk and the DATA
  a.driver->stop();
  b.driver->stop();
}

}  // namespace
}  // namespace acomms::drivers
