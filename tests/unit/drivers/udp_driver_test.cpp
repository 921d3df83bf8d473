#include "udp/udp_driver.h"

#include <gtest/gtest.h>

#include <asio/ip/udp.hpp>

#include "core/scheduler.h"

namespace acomms::drivers {
namespace {

using v1::ModemTransmission;

unsigned short free_udp_port() {
  asio::io_context io;
  asio::ip::udp::socket socket(io, asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  return socket.local_endpoint().port();
}

bool run_until(asio::io_context& io, const std::function<bool()>& done,
               std::chrono::milliseconds timeout = std::chrono::seconds(2)) {
  auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done() && std::chrono::steady_clock::now() < deadline) {
    if (io.stopped()) io.restart();
    io.run_one_for(std::chrono::milliseconds(10));
  }
  return done();
}

std::string local(unsigned short port) { return "127.0.0.1:" + std::to_string(port); }

struct UdpNode {
  UdpNode(asio::io_context& io, core::Scheduler& scheduler, int id, unsigned short port, unsigned short peer,
          v1::DriverConfig config = {}) {
    config.set_name("udp");
    config.set_modem_id(id);
    config.mutable_udp()->set_listen(local(port));
    config.mutable_udp()->add_peers(local(peer));
    driver = std::make_unique<UdpDriver>(config, scheduler, io);
    link::DriverCallbacks callbacks;
    callbacks.on_receive = [this](const ModemTransmission& tx) { received.push_back(tx); };
    callbacks.on_data_request = [this](ModemTransmission* tx) {
      requests.push_back(*tx);
      for (const auto& frame : frames) tx->add_frame(frame);
    };
    callbacks.on_transmit_result = [this](const ModemTransmission& tx, bool ok, const std::string& error) {
      results.push_back({tx, ok, error});
    };
    callbacks.on_raw = [this](std::string_view bytes, bool outgoing) {
      (outgoing ? raw_out : raw_in).emplace_back(bytes);
    };
    driver->start(callbacks);
  }
  struct Result {
    ModemTransmission tx;
    bool ok;
    std::string error;
  };
  std::unique_ptr<UdpDriver> driver;
  std::vector<std::string> frames{"payload"};
  std::vector<ModemTransmission> received, requests;
  std::vector<Result> results;
  std::vector<std::string> raw_in, raw_out;
};

class UdpDriverTest : public ::testing::Test {
 protected:
  asio::io_context io_;
  core::SystemClock clock_;
  core::AsioScheduler scheduler_{io_, clock_};
  unsigned short port_a_ = free_udp_port(), port_b_ = free_udp_port();
};

TEST_F(UdpDriverTest, RoundTripWithSoftwareAck) {
  UdpNode a(io_, scheduler_, 1, port_a_, port_b_), b(io_, scheduler_, 2, port_b_, port_a_);
  a.frames = {"f0", "f1", "f2"};
  ModemTransmission tx;
  tx.set_src(1);
  tx.set_dest(2);
  tx.set_rate(1);
  a.driver->initiate_transmission(tx);
  ASSERT_EQ(a.requests.size(), 1u);
  EXPECT_EQ(a.requests[0].max_num_frames(), 3u);  // Micro-Modem rate 1: 3 x 64
  EXPECT_EQ(a.requests[0].max_frame_bytes(), 64u);
  ASSERT_EQ(a.results.size(), 1u);
  EXPECT_TRUE(a.results[0].ok) << a.results[0].error;

  ASSERT_TRUE(run_until(io_, [&] { return !a.received.empty(); }));
  ASSERT_EQ(b.received.size(), 1u);
  EXPECT_EQ(b.received[0].src(), 1);
  ASSERT_EQ(b.received[0].frame_size(), 3);
  EXPECT_EQ(b.received[0].frame(2), "f2");
  const auto& ack = a.received[0];
  EXPECT_EQ(ack.type(), ModemTransmission::ACK);
  EXPECT_EQ(ack.src(), 2);
  EXPECT_EQ(ack.dest(), 1);
  EXPECT_EQ(ack.acked_frame_size(), 3);
  // Raw bytes both ways: the serialized transmissions.
  ASSERT_EQ(a.raw_out.size(), 1u);
  ModemTransmission on_wire;
  ASSERT_TRUE(on_wire.ParseFromString(a.raw_out[0]));
  EXPECT_EQ(on_wire.frame(0), "f0");
  EXPECT_EQ(b.raw_in.size(), 1u);
}

TEST_F(UdpDriverTest, PollMakesThePeerSendItsData) {
  UdpNode a(io_, scheduler_, 1, port_a_, port_b_), b(io_, scheduler_, 2, port_b_, port_a_);
  b.frames = {"polled data"};
  ModemTransmission poll;
  poll.set_src(2);
  poll.set_dest(1);
  poll.set_rate(0);
  a.driver->initiate_transmission(poll);
  EXPECT_TRUE(a.requests.empty());
  ASSERT_TRUE(run_until(io_, [&] { return !a.received.empty() && !b.received.empty(); }));
  ASSERT_EQ(b.requests.size(), 1u);
  EXPECT_EQ(b.requests[0].dest(), 1);
  EXPECT_EQ(a.received[0].src(), 2);
  EXPECT_EQ(a.received[0].frame(0), "polled data");
  EXPECT_EQ(b.received[0].type(), ModemTransmission::ACK);  // A acknowledged B's data
}

TEST_F(UdpDriverTest, ConfiguredLimitsOverrideTheRateTable) {
  v1::DriverConfig config;
  config.mutable_udp()->set_max_frame_bytes(1000);
  config.mutable_udp()->set_max_num_frames(2);
  UdpNode a(io_, scheduler_, 1, port_a_, port_b_, config);
  a.frames = {std::string(1000, 'x')};
  ModemTransmission tx;
  tx.set_src(1);
  tx.set_rate(0);
  a.driver->initiate_transmission(tx);
  ASSERT_EQ(a.requests.size(), 1u);
  EXPECT_EQ(a.requests[0].max_frame_bytes(), 1000u);
  EXPECT_EQ(a.requests[0].max_num_frames(), 2u);
  EXPECT_TRUE(a.results.at(0).ok);
  EXPECT_EQ(a.results[0].tx.dest(), 0);  // not chosen by the queues: broadcast
}

TEST_F(UdpDriverTest, GarbageDatagramIsCountedNotFatal) {
  UdpNode a(io_, scheduler_, 1, port_a_, port_b_), b(io_, scheduler_, 2, port_b_, port_a_);
  {
    asio::ip::udp::socket junk(io_, asio::ip::udp::endpoint(asio::ip::udp::v4(), 0));
    auto to = asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), port_b_);
    junk.send_to(asio::buffer(std::string("\x0f\xff\xff garbage")), to);  // does not parse
    junk.send_to(asio::buffer(std::string()), to);                        // parses, but no src
  }
  ASSERT_TRUE(run_until(io_, [&] { return b.driver->stats().garbage == 2; }));
  ModemTransmission tx;
  tx.set_src(1);
  tx.set_dest(2);
  a.driver->initiate_transmission(tx);
  ASSERT_TRUE(run_until(io_, [&] { return !b.received.empty(); }));
  EXPECT_EQ(b.driver->stats().garbage, 2u);
  EXPECT_NO_THROW(b.driver->do_work());
}

TEST_F(UdpDriverTest, PortInUseFailsStartWithTheAddress) {
  UdpNode a(io_, scheduler_, 1, port_a_, port_b_);
  v1::DriverConfig config;
  config.mutable_udp()->set_listen(local(port_a_));
  UdpDriver second(config, scheduler_, io_);
  try {
    second.start({});
    FAIL();
  } catch (const link::DriverError& e) {
    EXPECT_NE(std::string(e.what()).find(local(port_a_)), std::string::npos) << e.what();
  }
  EXPECT_THROW(second.do_work(), link::DriverError);
}

TEST_F(UdpDriverTest, BadConfigIsRejected) {
  v1::DriverConfig config;
  EXPECT_THROW(UdpDriver(config, scheduler_, io_), std::invalid_argument);  // no listen
  config.mutable_udp()->set_listen("127.0.0.1:1");
  config.mutable_udp()->add_peers("nowhere");
  EXPECT_THROW(UdpDriver(config, scheduler_, io_), std::invalid_argument);
}

}  // namespace
}  // namespace acomms::drivers
