// The sim and udp drivers live on the core thread (link/driver.h): their
// state (arrivals, timers, the socket, the sequence's callbacks) has no
// lock. So start(), stop() and sending assert it: while a core thread runs,
// a call from another thread (a gRPC handler, a test's own thread) aborts
// naming the function, instead of racing the link (core/core_thread.h).

#include <gtest/gtest.h>

#include <asio/io_context.hpp>

#include <chrono>
#include <memory>

#include "core/event_loop.h"
#include "core/logging.h"
#include "core/scheduler.h"
#include "sim/sim_channel.h"
#include "sim/sim_driver.h"
#include "udp/udp_driver.h"

namespace acomms::drivers {
namespace {

using std::chrono::seconds;

v1::DriverConfig sim_config() {
  v1::DriverConfig config;
  config.set_name("sim");
  config.set_modem_id(1);
  return config;
}

v1::DriverConfig udp_config() {
  v1::DriverConfig config;
  config.set_name("udp");
  config.set_modem_id(1);
  // Never bound: the assertion comes first.
  config.mutable_udp()->set_listen("127.0.0.1:0");
  return config;
}

// Runs `call` on the test's thread while a core thread runs.
template <typename Call>
void off_the_core_thread(Call call) {
  core::configure_logging(v1::INFO);  // the daemon's logger: stderr
  core::EventLoop core;
  core.start();
  call();
}

class DriverCoreThreadDeathTest : public ::testing::Test {
 protected:
  void SetUp() override { GTEST_FLAG_SET(death_test_style, "threadsafe"); }

  core::SimulatedScheduler scheduler_{core::Clock::time_point(seconds(1'700'000'000))};
  asio::io_context io_;
};

TEST_F(DriverCoreThreadDeathTest, SimStartFromAnotherThreadWhileTheCoreRuns) {
  SimDriver driver(sim_config(), scheduler_, SimChannel::create(1));
  EXPECT_DEATH(off_the_core_thread([&] { driver.start({}); }), "SimDriver::start.* must run on the core thread");
}

TEST_F(DriverCoreThreadDeathTest, SimStopFromAnotherThreadWhileTheCoreRuns) {
  SimDriver driver(sim_config(), scheduler_, SimChannel::create(1));
  driver.start({});  // no core runs yet: the test's thread owns the driver
  EXPECT_DEATH(off_the_core_thread([&] { driver.stop(); }), "SimDriver::stop.* must run on the core thread");
  driver.stop();
}

TEST_F(DriverCoreThreadDeathTest, UdpStartFromAnotherThreadWhileTheCoreRuns) {
  UdpDriver driver(udp_config(), scheduler_, io_);
  EXPECT_DEATH(off_the_core_thread([&] { driver.start({}); }), "UdpDriver::start.* must run on the core thread");
}

TEST_F(DriverCoreThreadDeathTest, UdpStopFromAnotherThreadWhileTheCoreRuns) {
  UdpDriver driver(udp_config(), scheduler_, io_);
  EXPECT_DEATH(off_the_core_thread([&] { driver.stop(); }), "UdpDriver::stop.* must run on the core thread");
}

// The same calls pass on the core thread itself.
TEST(DriverCoreThread, StartAndStopPassOnTheCoreThread) {
  core::SimulatedScheduler scheduler(core::Clock::time_point(seconds(1'700'000'000)));
  asio::io_context io;
  SimDriver sim(sim_config(), scheduler, SimChannel::create(1));
  UdpDriver udp(udp_config(), scheduler, io);
  core::EventLoop core;
  core.start();
  core.call([&] {
    sim.start({});
    sim.stop();
    udp.start({});
    udp.stop();
  });
  core.stop();
}

}  // namespace
}  // namespace acomms::drivers
