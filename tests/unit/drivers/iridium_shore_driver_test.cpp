// The "iridium_shore" driver against the fake DirectIP gateway
// (tests/fakes/iridium), over real loopback sockets: real time is what the
// sockets run on, so limits are set to fractions of a second.

#include "iridium_shore/iridium_shore_driver.h"

#include <gtest/gtest.h>

#include <asio/ip/tcp.hpp>

#include <deque>

#include "core/scheduler.h"
#include "fake_directip_gateway.h"
#include "link/driver_registry.h"

namespace acomms::drivers {
namespace {

using fake_iridium::FakeDirectIpGateway;
using v1::ModemTransmission;

const std::string kImei = "300234010000001";
constexpr int32_t kShore = 1, kVehicle = 7;

unsigned short free_tcp_port() {
  asio::io_context io;
  asio::ip::tcp::acceptor acceptor(io, asio::ip::tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  return acceptor.local_endpoint().port();
}

// The queues and the store, as the driver sees them through its callbacks.
struct FakeLink {
  std::map<int32_t, std::deque<std::string>> queued;  // frames by destination, acked ones removed
  std::vector<ModemTransmission> received, acks, requests;
  std::vector<std::pair<ModemTransmission, bool>> results;
  bool hold_durable = false;
  std::vector<std::function<void()>> waiting_for_durable;

  link::DriverCallbacks callbacks() {
    link::DriverCallbacks c;
    c.on_receive = [this](const ModemTransmission& t) {
      if (t.type() != ModemTransmission::ACK) return received.push_back(t);
      acks.push_back(t);
      if (!queued[t.src()].empty()) queued[t.src()].pop_front();
    };
    c.on_data_request = [this](ModemTransmission* t) {
      requests.push_back(*t);
      auto& frames = queued[t->dest()];
      t->add_frame(frames.empty() ? "" : frames.front());  // the link's empty frame when nothing waits
    };
    c.on_transmit_result = [this](const ModemTransmission& t, bool ok, const std::string&) {
      results.emplace_back(t, ok);
    };
    c.after_receipt_durable = [this](std::function<void()> then) {
      if (hold_durable) return waiting_for_durable.push_back(std::move(then));
      then();
    };
    return c;
  }
  void make_durable() {
    for (auto& then : waiting_for_durable) then();
    waiting_for_durable.clear();
  }
};

class IridiumShoreDriverTest : public ::testing::Test {
 protected:
  IridiumShoreDriverTest() { make_gateway(); }

  void make_gateway(bool confirmations = false) {
    gateway_.reset();
    FakeDirectIpGateway::Options options;
    options.shore_mo_address = "127.0.0.1:" + std::to_string(mo_port_);
    options.mo_retry = std::chrono::milliseconds(100);
    options.expect_mo_confirmation = confirmations;
    gateway_ = std::make_unique<FakeDirectIpGateway>(options);
  }

  v1::DriverConfig config() {
    v1::DriverConfig c;
    c.set_name("iridium_shore");
    c.set_modem_id(kShore);
    auto* shore = c.mutable_iridium_shore();
    shore->set_mo_listen("127.0.0.1:" + std::to_string(mo_port_));
    shore->set_mt_gateway(gateway_->mt_address());
    auto* modem = shore->add_modems();
    modem->set_imei(kImei);
    modem->set_modem_id(kVehicle);
    // Short enough for a test, long enough for a loaded CI machine.
    shore->set_mo_read_timeout_s(0.5);
    shore->set_mt_confirmation_timeout_s(1.0);
    shore->set_mt_check_interval_s(0.05);
    shore->set_mt_retry_min_s(0.2);
    shore->set_mt_refused_wait_s(60);
    shore->set_mo_confirmation(gateway_confirms_);
    return c;
  }

  void start(v1::DriverConfig c) {
    driver_ = std::make_unique<IridiumShoreDriver>(c, scheduler_, io_);
    driver_->start(link_.callbacks());
  }
  void start() { start(config()); }

  // Runs the loop (and the driver's do_work) until `done` or 5 s.
  bool run_until(const std::function<bool()>& done, std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
    auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!done() && std::chrono::steady_clock::now() < deadline) {
      if (io_.stopped()) io_.restart();
      io_.run_one_for(std::chrono::milliseconds(10));
      if (driver_) driver_->do_work();
    }
    return done();
  }
  void run_for(std::chrono::milliseconds duration) {
    run_until([] { return false; }, duration);
  }
  uint64_t bad(const std::string& kind) {
    auto counters = driver_->counters();
    auto it = counters.bad_input.find(kind);
    return it == counters.bad_input.end() ? 0 : it->second;
  }

  asio::io_context io_;
  core::SystemClock clock_;
  core::AsioScheduler scheduler_{io_, clock_};
  unsigned short mo_port_ = free_tcp_port();
  bool gateway_confirms_ = false;
  std::unique_ptr<FakeDirectIpGateway> gateway_;
  FakeLink link_;
  std::unique_ptr<IridiumShoreDriver> driver_;
};

TEST_F(IridiumShoreDriverTest, MoArrivesAsDataFromTheVehiclesModemId) {
  start();
  gateway_->mo_received(kImei, 41, "hello shore");
  ASSERT_TRUE(run_until([&] { return link_.received.size() == 1 && gateway_->mo_delivered() == 1; }));
  const ModemTransmission& rx = link_.received[0];
  EXPECT_EQ(rx.type(), ModemTransmission::DATA);
  EXPECT_EQ(rx.src(), kVehicle);
  EXPECT_EQ(rx.dest(), kShore);
  EXPECT_FALSE(rx.ack_requested());  // no software ACK over the satellite
  ASSERT_EQ(rx.frame_size(), 1);
  EXPECT_EQ(rx.frame(0), "hello shore");
  EXPECT_EQ(driver_->stats().mo_handed_up, 1u);
}

TEST_F(IridiumShoreDriverTest, RedeliveredMoIsHandedUpOnce) {
  start();
  gateway_->mo_received(kImei, 41, "once");
  gateway_->mo_received(kImei, 41, "once");  // the gateway redelivers, or the modem resent
  gateway_->mo_received(kImei, 42, "once");  // a new MO with the same bytes
  ASSERT_TRUE(run_until([&] { return gateway_->mo_delivered() == 3; }));
  run_for(std::chrono::milliseconds(100));
  ASSERT_EQ(link_.received.size(), 2u);
  EXPECT_EQ(driver_->stats().mo_duplicates, 1u);
  EXPECT_EQ(driver_->stats().mo_handed_up, 2u);
}

TEST_F(IridiumShoreDriverTest, ConfirmationWaitsUntilTheMoIsDurable) {
  gateway_confirms_ = true;
  make_gateway(/*confirmations=*/true);
  link_.hold_durable = true;
  start();
  gateway_->mo_received(kImei, 5, "precious");
  ASSERT_TRUE(run_until([&] { return link_.received.size() == 1; }));
  run_for(std::chrono::milliseconds(200));
  EXPECT_EQ(gateway_->mo_delivered(), 0u);  // handed up, not yet durable: not answered
  link_.make_durable();
  ASSERT_TRUE(run_until([&] { return gateway_->mo_delivered() == 1; }));
  EXPECT_EQ(gateway_->mo_pending(), 0u);
}

TEST_F(IridiumShoreDriverTest, ShoreRestartWithAnMoOutstandingLosesNothing) {
  gateway_confirms_ = true;
  make_gateway(/*confirmations=*/true);
  link_.hold_durable = true;
  start();
  gateway_->mo_received(kImei, 9, "do not lose me");
  ASSERT_TRUE(run_until([&] { return link_.received.size() == 1; }));
  // The shore dies before its store committed: the connection closes
  // unanswered, so the gateway keeps the MO and retries a shore that is down.
  driver_.reset();
  link_ = FakeLink{};
  size_t attempts = gateway_->mo_attempts();
  ASSERT_TRUE(run_until([&] { return gateway_->mo_attempts() >= attempts + 2; }));
  EXPECT_EQ(gateway_->mo_pending(), 1u);
  EXPECT_EQ(gateway_->mo_delivered(), 0u);
  start();  // the same port
  ASSERT_TRUE(run_until([&] { return gateway_->mo_delivered() == 1; }));
  ASSERT_EQ(link_.received.size(), 1u);
  EXPECT_EQ(link_.received[0].frame(0), "do not lose me");
}

TEST_F(IridiumShoreDriverTest, UnknownImeiIsLoggedAndCountedNotHandedUp) {
  start();
  gateway_->mo_received("300234019999999", 1, "stranger");
  gateway_->mo_received(kImei, 2, "friend");
  ASSERT_TRUE(run_until([&] { return gateway_->mo_delivered() == 2; }));
  run_for(std::chrono::milliseconds(50));
  ASSERT_EQ(link_.received.size(), 1u);
  EXPECT_EQ(link_.received[0].frame(0), "friend");
  EXPECT_EQ(bad("MO from an unknown IMEI"), 1u);
}

TEST_F(IridiumShoreDriverTest, WrongLengthsAndOversizeAreRefusedAndCountedAndTheServerGoesOn) {
  start();
  std::string good = FakeDirectIpGateway::mo_message(kImei, 3, "abc");
  // The overall length says one more byte than comes: the shore waits for
  // it, then gives up at its read limit.
  std::string short_by_one = good.substr(0, good.size() - 1);
  std::string lying_ie = good;
  lying_ie[lying_ie.size() - 4] = 0x09;  // the payload IE claims 9 bytes, 3 follow
  std::string oversized = FakeDirectIpGateway::mo_message(kImei, 4, std::string(341, 'o'));
  std::string unknown_ie = good;
  unknown_ie += std::string("\x7f\x00\x01\x00", 4);
  unknown_ie[2] = static_cast<char>(unknown_ie.size() - 3);
  gateway_->push_raw_mo(lying_ie);
  gateway_->push_raw_mo(oversized);
  gateway_->push_raw_mo(short_by_one);
  gateway_->push_raw_mo(unknown_ie);
  ASSERT_TRUE(run_until([&] { return gateway_->mo_pending() == 0; }));
  EXPECT_EQ(bad("MO refused"), 2u);        // the lying IE and the oversized payload
  EXPECT_EQ(bad("MO read timeout"), 1u);   // the short one never completes
  EXPECT_EQ(bad("MO unknown IE"), 1u);
  ASSERT_EQ(link_.received.size(), 1u);    // the message with the unknown IE, its payload intact
  EXPECT_EQ(link_.received[0].frame(0), "abc");
  gateway_->mo_received(kImei, 10, "still serving");
  ASSERT_TRUE(run_until([&] { return link_.received.size() == 2; }));
}

TEST_F(IridiumShoreDriverTest, HangingConnectionIsDroppedWithoutBlockingOthers) {
  start();
  std::string mo = FakeDirectIpGateway::mo_message(kImei, 3, "abc");
  gateway_->open_hanging_mo(mo.substr(0, 10));
  gateway_->mo_received(kImei, 4, "meanwhile");
  ASSERT_TRUE(run_until([&] { return link_.received.size() == 1; }));
  ASSERT_TRUE(run_until([&] { return gateway_->hanging_closed_by_shore() == 1; }));
  EXPECT_EQ(bad("MO read timeout"), 1u);
}

TEST_F(IridiumShoreDriverTest, ConnectionsBeyondTheBoundWaitTheirTurn) {
  v1::DriverConfig c = config();
  c.mutable_iridium_shore()->set_max_mo_connections(1);
  start(c);
  gateway_->open_hanging_mo(FakeDirectIpGateway::mo_message(kImei, 3, "abc").substr(0, 5));
  run_for(std::chrono::milliseconds(100));  // the hanging connection holds the one place
  gateway_->mo_received(kImei, 4, "after the slow one");
  // Not served (it waits in the backlog) until the read limit frees the place.
  ASSERT_TRUE(run_until([&] { return !link_.received.empty(); }));
  EXPECT_EQ(bad("MO read timeout"), 1u);  // the slow one was dropped first
  EXPECT_EQ(link_.received[0].frame(0), "after the slow one");
  EXPECT_TRUE(run_until([&] { return gateway_->hanging_closed_by_shore() == 1; }));
}

TEST_F(IridiumShoreDriverTest, UnreachableShoreGetsTheMoOnceItIsBack) {
  start();
  gateway_->set_shore_reachable(false);
  gateway_->mo_received(kImei, 8, "kept at the gateway");
  ASSERT_TRUE(run_until([&] { return gateway_->mo_attempts() >= 2; }));
  EXPECT_TRUE(link_.received.empty());
  gateway_->set_shore_reachable(true);
  ASSERT_TRUE(run_until([&] { return gateway_->mo_delivered() == 1; }));
  ASSERT_EQ(link_.received.size(), 1u);
  EXPECT_EQ(link_.received[0].frame(0), "kept at the gateway");
}

TEST_F(IridiumShoreDriverTest, MalformedMtConfirmationIsCountedAndTheMtResent) {
  start();
  gateway_->garble_next_mt_confirmation();
  link_.queued[kVehicle] = {"garbled"};
  ASSERT_TRUE(run_until([&] { return !link_.acks.empty(); }));
  EXPECT_EQ(bad("MT confirmation refused"), 1u);
  auto submissions = gateway_->mt_submissions();
  ASSERT_EQ(submissions.size(), 2u);
  EXPECT_EQ(submissions[0].client_id, submissions[1].client_id);
  EXPECT_EQ(gateway_->mt_queued(kImei), 1);
}

TEST_F(IridiumShoreDriverTest, MtQueuedAtTheGatewayIsReportedSentAndAcknowledged) {
  start();
  link_.queued[kVehicle] = {"come home"};
  ASSERT_TRUE(run_until([&] { return !link_.acks.empty(); }));
  auto submissions = gateway_->mt_submissions();
  ASSERT_EQ(submissions.size(), 1u);
  EXPECT_EQ(submissions[0].imei, kImei);
  EXPECT_EQ(submissions[0].flags, 0x0020);  // assign MTMSN
  EXPECT_EQ(submissions[0].status, 1);
  auto mt = gateway_->take_mt(kImei);
  ASSERT_TRUE(mt);
  EXPECT_EQ(mt->payload, "come home");
  EXPECT_EQ(mt->mtmsn, submissions[0].client_id);
  EXPECT_EQ(link_.acks[0].src(), kVehicle);
  EXPECT_EQ(link_.acks[0].dest(), kShore);
  ASSERT_EQ(link_.acks[0].acked_frame_size(), 1);
  ASSERT_FALSE(link_.results.empty());
  EXPECT_TRUE(link_.results.back().second);
  EXPECT_EQ(link_.requests[0].max_frame_bytes(), 270u);
  EXPECT_EQ(link_.requests[0].dest(), kVehicle);
  run_for(std::chrono::milliseconds(200));
  EXPECT_EQ(gateway_->mt_submissions().size(), 1u);  // nothing more queued: nothing more sent
}

TEST_F(IridiumShoreDriverTest, QueueFullIsRetriedAfterABackOffWithTheSameMtmsn) {
  start();
  gateway_->refuse_next_mt(-5);
  link_.queued[kVehicle] = {"retry me"};
  ASSERT_TRUE(run_until([&] { return !link_.acks.empty(); }));
  auto submissions = gateway_->mt_submissions();
  ASSERT_EQ(submissions.size(), 2u);
  EXPECT_EQ(submissions[0].status, -5);
  EXPECT_EQ(submissions[1].status, 1);
  EXPECT_EQ(submissions[0].client_id, submissions[1].client_id);
  EXPECT_EQ(driver_->stats().mt_retry_later, 1u);
  EXPECT_FALSE(link_.results.front().second);
  EXPECT_EQ(gateway_->mt_queued(kImei), 1);
}

TEST_F(IridiumShoreDriverTest, MtWithoutConfirmationIsResentWithTheSameMtmsn) {
  start();
  gateway_->hang_next_mt();
  link_.queued[kVehicle] = {"are you there"};
  ASSERT_TRUE(run_until([&] { return !link_.acks.empty(); }));
  auto submissions = gateway_->mt_submissions();
  ASSERT_EQ(submissions.size(), 2u);
  EXPECT_FALSE(submissions[0].answered);
  EXPECT_TRUE(submissions[1].answered);
  EXPECT_EQ(submissions[0].client_id, submissions[1].client_id);  // the vehicle can tell a second copy
  EXPECT_EQ(driver_->stats().mt_retry_later, 1u);
  EXPECT_EQ(gateway_->mt_queued(kImei), 1);
}

TEST_F(IridiumShoreDriverTest, RefusedMtWaitsAndStaysQueued) {
  start();
  gateway_->refuse_next_mt(-2);  // IMEI not provisioned
  link_.queued[kVehicle] = {"not yet"};
  ASSERT_TRUE(run_until([&] { return driver_->stats().mt_refused == 1; }));
  run_for(std::chrono::milliseconds(300));
  EXPECT_EQ(gateway_->mt_submissions().size(), 1u);  // mt_refused_wait_s (60 s) not over
  EXPECT_TRUE(link_.acks.empty());
  EXPECT_EQ(link_.queued[kVehicle].size(), 1u);
  ASSERT_FALSE(link_.results.empty());
  EXPECT_FALSE(link_.results.back().second);
}

TEST_F(IridiumShoreDriverTest, AFrameAboveTheMtLimitIsNeverSubmitted) {
  start();
  link_.queued[kVehicle] = {std::string(271, 'x')};
  run_for(std::chrono::milliseconds(300));
  EXPECT_FALSE(link_.requests.empty());
  EXPECT_TRUE(gateway_->mt_submissions().empty());
}

TEST_F(IridiumShoreDriverTest, GatewayDownIsRetriedNotFatal) {
  v1::DriverConfig c = config();
  c.mutable_iridium_shore()->set_mt_gateway("127.0.0.1:" + std::to_string(free_tcp_port()));
  start(c);
  link_.queued[kVehicle] = {"anyone"};
  ASSERT_TRUE(run_until([&] { return driver_->stats().mt_retry_later >= 2; }));
  EXPECT_TRUE(link_.acks.empty());
  EXPECT_EQ(link_.queued[kVehicle].size(), 1u);
}

TEST_F(IridiumShoreDriverTest, BadSettingsNameTheField) {
  auto refused = [&](const std::function<void(v1::DriverConfig&)>& change) -> std::string {
    v1::DriverConfig c = config();
    change(c);
    try {
      IridiumShoreDriver driver(c, scheduler_, io_);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(refused([](auto& c) { c.mutable_iridium_shore()->mutable_modems(0)->set_imei("12345"); }),
            "driver.iridium_shore.modems[0].imei \"12345\" is not 15 digits");
  EXPECT_EQ(refused([](auto& c) { c.mutable_iridium_shore()->mutable_modems(0)->set_modem_id(kShore); }),
            "driver.iridium_shore.modems[0].modem_id must be a vehicle's id: not 0 (broadcast) and not this node's "
            "own id");
  EXPECT_EQ(refused([](auto& c) { c.mutable_iridium_shore()->set_mt_max_bytes(271); }),
            "driver.iridium_shore.mt_max_bytes is 271, above the 9602/9603 MT limit of 270");
  EXPECT_NE(refused([](auto& c) { c.mutable_iridium_shore()->clear_mo_listen(); }).find("mo_listen"), std::string::npos);
}

TEST(IridiumShoreRegistryTest, IsRegisteredByName) {
  auto names = link::DriverRegistry::linked().names();
  EXPECT_NE(std::find(names.begin(), names.end(), "iridium_shore"), names.end());
}

}  // namespace
}  // namespace acomms::drivers
