// Drivers by name: every folder under plugins/drivers adds itself to
// link::DriverRegistry::linked(), with what it says about itself (the raw
// link log), and "sim" can be rebound to one channel.

#include <gtest/gtest.h>

#include "link/driver_registry.h"
#include "sim/sim_channel.h"
#include "sim/sim_driver.h"
#include "sim/sim_plugin.h"

namespace acomms {
namespace {

using std::chrono::seconds;

TEST(RegisterDriversTest, SimAndUdpByName) {
  link::DriverRegistry registry = link::DriverRegistry::linked();
  EXPECT_EQ(registry.names(), (std::vector<std::string>{"iridium", "iridium_shore", "micromodem", "sim", "udp"}));

  core::SimulatedScheduler scheduler(core::Clock::time_point(seconds(1'700'000'000)));
  v1::DriverConfig config;
  config.set_name("sim");
  auto alone = registry.create("sim", {config, scheduler});  // no listen: an isolated node
  ASSERT_NE(alone, nullptr);
  alone->start({});
  alone->stop();

  config.mutable_sim()->set_max_range_m(-1);
  try {
    registry.create("sim", {config, scheduler});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("driver.sim.max_range_m"), std::string::npos);
  }

  v1::DriverConfig udp;
  udp.mutable_udp()->set_listen("127.0.0.1:0");
  EXPECT_THROW(registry.create("udp", {udp, scheduler}), std::invalid_argument);  // no event loop
  asio::io_context io;
  link::DriverContext with_io{udp, scheduler, &io};
  auto driver = registry.create("udp", with_io);
  ASSERT_NE(driver, nullptr);
  driver->start({});
  driver->stop();
}

TEST(RegisterDriversTest, MicroModemByNameNeedsAnEventLoopAndAPort) {
  link::DriverRegistry registry = link::DriverRegistry::linked();
  core::SimulatedScheduler scheduler(core::Clock::time_point(seconds(1'700'000'000)));
  v1::DriverConfig config;
  config.set_name("micromodem");
  config.mutable_micromodem()->set_port("tcp:127.0.0.1:1");
  EXPECT_THROW(registry.create("micromodem", {config, scheduler}), std::invalid_argument);  // no event loop
  asio::io_context io;
  auto driver = registry.create("micromodem", {config, scheduler, &io});
  ASSERT_NE(driver, nullptr);
  config.mutable_micromodem()->clear_port();
  try {
    registry.create("micromodem", {config, scheduler, &io});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("driver.micromodem.port"), std::string::npos);
  }
  config.mutable_micromodem()->set_port("tcp:nohostport");
  EXPECT_THROW(registry.create("micromodem", {config, scheduler, &io}), std::invalid_argument);
}

TEST(RegisterDriversTest, UnknownNameListsTheLinkedDrivers) {
  core::SimulatedScheduler scheduler(core::Clock::time_point(seconds(1'700'000'000)));
  v1::DriverConfig config;
  try {
    link::DriverRegistry::linked().create("micromodem9", {config, scheduler});
    FAIL() << "built a driver nobody registered";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "no driver \"micromodem9\" (known: iridium, iridium_shore, micromodem, sim, udp)");
  }
}

// The daemon keeps a raw link log only where the driver asks for one: the
// Micro-Modem's sentences (4 MiB per file unless configured), not the
// simulator's or udp's datagrams.
TEST(RegisterDriversTest, OnlyTheMicroModemAsksForARawLogOfFourMiBUnlessConfigured) {
  const link::DriverRegistry& registry = link::DriverRegistry::linked();
  EXPECT_FALSE(registry.traits("sim").raw_log_bytes);
  EXPECT_FALSE(registry.traits("udp").raw_log_bytes);
  const auto& micromodem = registry.traits("micromodem").raw_log_bytes;
  ASSERT_TRUE(micromodem);
  v1::DriverConfig config;
  EXPECT_EQ(micromodem(config), uint64_t{4} << 20);
  config.mutable_micromodem()->set_raw_log_bytes(65536);
  EXPECT_EQ(micromodem(config), 65536u);
  EXPECT_THROW(registry.traits("micromodem9"), std::invalid_argument);
}

TEST(RegisterDriversTest, SimChannelDriverPutsEveryNodeOnTheChannel) {
  link::DriverRegistry registry = link::DriverRegistry::linked();
  auto channel = drivers::SimChannel::create(5);
  drivers::register_sim_channel_driver(registry, channel);
  core::SimulatedScheduler scheduler(core::Clock::time_point(seconds(1'700'000'000)));
  v1::DriverConfig one, two;
  one.set_modem_id(1);
  two.set_modem_id(2);
  two.mutable_sim()->mutable_position()->set_x(1500);
  auto a = registry.create("sim", {one, scheduler});
  auto b = registry.create("sim", {two, scheduler});
  int received = 0;
  link::DriverCallbacks on_b;
  on_b.on_receive = [&](const v1::ModemTransmission&) { ++received; };
  link::DriverCallbacks on_a;
  on_a.on_data_request = [](v1::ModemTransmission* tx) { tx->add_frame(std::string("x")); };
  a->start(on_a);
  b->start(on_b);
  EXPECT_EQ(channel->size(), 2u);
  v1::ModemTransmission tx;
  tx.set_src(1);
  tx.set_dest(2);
  a->initiate_transmission(tx);
  scheduler.run_for(seconds(5));
  EXPECT_EQ(received, 1);
}

}  // namespace
}  // namespace acomms
