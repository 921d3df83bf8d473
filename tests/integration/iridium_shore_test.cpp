// A shore node on Iridium, end to end: a real acommsd whose only link is
// driver "iridium_shore" (MAC "none"), against the fake DirectIP gateway
// (tests/fakes/iridium). What a vehicle's modem sends (an MO the gateway
// pushes) reaches a subscriber once, even when the gateway delivers it
// twice; what `acommsctl send` queues for the vehicle's modem id becomes an
// MT queued at the gateway for the vehicle's IMEI, and leaves the queue.

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <ctime>
#include <filesystem>

#include "child_process.h"
#include "daemon_harness.h"
#include "dccl/codec.h"
#include "fake_directip_gateway.h"
#include "stream_subscriber.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using fake_iridium::FakeDirectIpGateway;

const std::string kImei = "300234010000001";
const std::string kProto = std::string(ACOMMS_SOURCE_DIR) + "/examples/messages.proto";

std::string roles(const std::string& type) {
  return "  type { type: \"" + type + "\" policy { ttl_s: 600 }\n" +
         "         roles { source_field: \"src\" destination_field: \"dest\" timestamp_field: \"time\" } }\n";
}

TEST(IridiumShore, MoReachesASubscriberOnceAndSendQueuesAnMtAtTheGateway) {
  fs::path dir = fs::path("/tmp") / ("acomms-iridium-shore-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const int mo_port = free_tcp_port();
  FakeDirectIpGateway gateway({.shore_mo_address = "127.0.0.1:" + std::to_string(mo_port),
                               .mo_retry = 200ms,
                               .expect_mo_confirmation = true});
  const std::string socket = (dir / "shore.sock").string();
  DaemonConfig config;
  config.data_dir = dir / "data";
  config.unix_socket = socket;
  config.proto_file = kProto;
  config.rest = "driver { name: \"iridium_shore\" modem_id: 1 iridium_shore {\n"
                "  mo_listen: \"127.0.0.1:" + std::to_string(mo_port) + "\"\n"
                "  mt_gateway: \"" + gateway.mt_address() + "\"\n"
                "  modems { imei: \"" + kImei + "\" modem_id: 2 }\n"
                "  mo_confirmation: true\n"
                "  mt_check_interval_s: 0.2\n"
                "} }\n"
                "mac { name: \"none\" }\n"
                "queue {\n" + roles("example.Status") + roles("example.Command") + "}\n";
  config.write(dir / "shore.conf");
  ChildProcess daemon(ACOMMSD_BINARY, {"--config", (dir / "shore.conf").string()}, (dir / "run").string());
  ASSERT_TRUE(wait_serving(daemon, socket)) << daemon.stderr_text();

  // MO: the vehicle (modem id 2) sent a Status; the gateway delivers it twice.
  dccl::Codec codec;
  codec.load(kProto);
  auto status = codec.new_message("example.Status");
  const auto* d = status->GetDescriptor();
  const auto* r = status->GetReflection();
  r->SetInt32(status.get(), d->FindFieldByName("src"), 2);
  r->SetInt32(status.get(), d->FindFieldByName("dest"), 1);
  r->SetDouble(status.get(), d->FindFieldByName("time"), static_cast<double>(std::time(nullptr)));
  r->SetDouble(status.get(), d->FindFieldByName("x"), 120);
  r->SetDouble(status.get(), d->FindFieldByName("y"), -40);
  r->SetDouble(status.get(), d->FindFieldByName("depth"), 0);
  const std::string mo_payload = codec.encode(*status);
  StreamSubscriber subscriber(socket, "example.Status");
  gateway.mo_received(kImei, 17, mo_payload);
  gateway.mo_received(kImei, 17, mo_payload);
  EXPECT_TRUE(wait_until([&] { return gateway.mo_delivered() == 2; }, 20s)) << daemon.stderr_text();
  EXPECT_TRUE(subscriber.wait_for([](const auto& received) { return !received.empty(); }, 10s))
      << daemon.stderr_text();
  std::this_thread::sleep_for(500ms);  // room for a wrong second delivery to show
  auto received = subscriber.received();
  ASSERT_EQ(received.size(), 1u) << daemon.stderr_text();
  EXPECT_NE(received[0].json().find("\"src\":2,\"dest\":1,"), std::string::npos) << received[0].json();
  EXPECT_NE(received[0].json().find("\"x\":120,"), std::string::npos) << received[0].json();

  // MT: the operator sends a Command to the vehicle's modem id.
  RunResult sent = run(ACOMMSCTL_BINARY, {"--socket", socket, "send", "example.Command", "src=1", "dest=2",
                                          "time=" + std::to_string(std::time(nullptr)), "kind=HOLD", "seq=42"},
                       (dir / "ctl").string());
  ASSERT_EQ(sent.exit_code, 0) << sent.err;
  ASSERT_TRUE(wait_until([&] { return gateway.mt_queued(kImei) == 1; }, 20s)) << daemon.stderr_text();
  auto mt = gateway.take_mt(kImei);
  ASSERT_TRUE(mt);
  auto messages = codec.decode(mt->payload);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0]->GetTypeName(), "example.Command");
  const auto* seq = messages[0]->GetDescriptor()->FindFieldByName("seq");
  EXPECT_EQ(messages[0]->GetReflection()->GetUInt32(*messages[0], seq), 42u);
  EXPECT_EQ(gateway.mt_submissions().size(), 1u);
  // Acknowledged at the gateway: nothing of it stays queued.
  auto queued_commands = [&] {
    grpc::ClientContext context;
    v1::ListQueuedRequest request;
    request.set_type("example.Command");
    v1::ListQueuedResponse response;
    EXPECT_TRUE(api(socket)->ListQueued(&context, request, &response).ok());
    return response.messages_size();
  };
  EXPECT_TRUE(wait_until([&] { return queued_commands() == 0; }, 10s));

  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.wait(15s), std::optional<int>(0)) << daemon.stderr_text();
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace acomms::testing
