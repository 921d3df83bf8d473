// A real acommsd whose one link is the Iridium driver (mac "none") on the
// fake 9603 over TCP (the serial-to-TCP gateway form), with an in-memory
// SBD gateway in this process: `acommsctl send` to the shore's id ends as
// one MO at the gateway; an MT queued at the gateway (a ring alert) reaches
// a subscriber of the vehicle once; link status shows the modem and its
// last session. The fake's session transcript is printed for the record.
// The fake's sessions take 1 s here, the real ones 10-30 s.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <thread>

#include <google/protobuf/text_format.h>

#include "daemon_harness.h"
#include "dccl/codec.h"
#include "iridium_vehicle_link.h"
#include "stream_subscriber.h"
#include "tcp_modem_host.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using fake_iridium::FakeSbdConfig;
using fake_iridium::InMemorySbdGateway;
using fake_iridium::TcpModemHost;

constexpr int kVehicle = 2;
constexpr int kShore = 1;
constexpr const char* kImei = "300234010000001";

TEST(IridiumVehicle, SendEndsAsAnMoAndAQueuedMtReachesASubscriberOnce) {
  InMemorySbdGateway gateway;
  FakeSbdConfig modem;
  modem.session_time = 1s;
  modem.auto_ring = true;
  TcpModemHost host(gateway, modem);

  const fs::path dir = fs::path("/tmp") / ("acomms-iridium-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string socket = (dir / "vehicle.sock").string();
  const std::string proto = ACOMMS_SOURCE_DIR "/examples/messages.proto";
  std::ofstream(dir / "vehicle.conf")
      << DaemonConfig{.data_dir = dir / "vehicle", .unix_socket = socket, .proto_file = proto}.text()
      << iridium_vehicle_driver(kVehicle, host.port(), kShore, kImei, "mailbox_check_s: 30 send_check_s: 1")
      << "mac { name: \"none\" }\n"
      << "queue {\n"
      << "  type { type: \"example.Status\" roles { source_field: \"src\" destination_field: \"dest\" timestamp_field: \"time\" } }\n"
      << "  type { type: \"example.Command\" roles { source_field: \"src\" destination_field: \"dest\" timestamp_field: \"time\" } }\n"
      << "}\n";
  ChildProcess daemon(ACOMMSD_BINARY, {"--config", (dir / "vehicle.conf").string()}, (dir / "vehicle-log").string());
  ASSERT_TRUE(wait_serving(daemon, socket)) << daemon.stderr_text();
  auto logs = [&] { return daemon.stderr_text() + "\nfake 9603:\n" + host.transcript(); };

  // MO: a Status for the shore.
  RunResult sent = run(ACOMMSCTL_BINARY,
                       {"--socket", socket, "send", "example.Status", "dest=1", "x=120", "y=-40", "depth=0", "seq=7"},
                       (dir / "send").string());
  ASSERT_EQ(sent.exit_code, 0) << sent.err;
  ASSERT_TRUE(wait_until([&] { return !gateway.mo().empty(); }, 30s)) << logs();
  dccl::Codec codec;
  codec.load(proto, {ACOMMS_SOURCE_DIR "/api/proto"});
  auto mo = gateway.mo();
  ASSERT_EQ(mo.size(), 1u) << logs();
  EXPECT_EQ(mo[0].imei, kImei);
  auto messages = codec.decode(mo[0].payload);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0]->GetDescriptor()->full_name(), "example.Status");
  EXPECT_NE(messages[0]->ShortDebugString().find("seq: 7"), std::string::npos) << messages[0]->ShortDebugString();

  // MT: a Command from the shore, queued at the gateway; the fake rings.
  StreamSubscriber subscriber(socket, "example.Command");
  auto command = codec.new_message("example.Command");
  google::protobuf::TextFormat::ParseFromString(
      "src: 1 dest: 2 kind: GOTO x: 200 y: -50 depth: 30 seq: 5 time: " +
          std::to_string(static_cast<double>(std::time(nullptr))),
      command.get());
  gateway.queue_mt(kImei, codec.encode(*command));
  ASSERT_TRUE(subscriber.wait_for([](const auto& r) { return !r.empty(); }, 30s)) << logs();
  // Later mailbox checks do not bring it again.
  ASSERT_TRUE(wait_until([&] { return host.transcript().find("+SBDIXA") != std::string::npos; }, 10s)) << logs();
  std::this_thread::sleep_for(2s);  // a few more do_work rounds: nothing more may arrive
  auto received = subscriber.received();
  ASSERT_EQ(received.size(), 1u);
  EXPECT_TRUE(std::regex_search(received[0].json(), std::regex(R"("seq":\s*5\b)"))) << received[0].json();
  EXPECT_EQ(received[0].src(), kShore);

  v1::LinkStatusResponse status;
  {
    grpc::ClientContext context;
    ASSERT_TRUE(api(socket)->LinkStatus(&context, {}, &status).ok());
  }
  EXPECT_EQ(status.driver().name(), "iridium");
  EXPECT_NE(status.driver().modem().find(std::string("Iridium SBD ") + kImei), std::string::npos)
      << status.driver().modem();
  EXPECT_NE(status.driver().modem().find("last session"), std::string::npos) << status.driver().modem();
  EXPECT_GE(status.counters().acks_received(), 1u);  // the MO's success acknowledged its frame
  EXPECT_EQ(gateway.mo().size(), 1u);

  std::cout << "session transcript of the fake 9603:\n" << host.transcript();
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.wait(15s), std::optional<int>(0)) << daemon.stderr_text();
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace acomms::testing
