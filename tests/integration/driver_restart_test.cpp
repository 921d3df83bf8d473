// A driver whose transport is gone does not take the daemon down: with the
// udp driver's port held by someone else the daemon still serves and queues
// submitted messages; once the port is free the supervisor's restart brings
// the driver up and the queued messages go out.

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "acomms/v1/modem_transmission.pb.h"
#include "child_process.h"
#include "net_status_proto.h"
#include "daemon_harness.h"
#include "dccl/codec.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

TEST(DriverRestart, QueuedMessagesGoOutOnceTheTransportIsBack) {
  fs::path dir = fs::path("/tmp") / ("acomms-restart-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "net.proto") << kNetStatusProto;
  const int listen_port = free_udp_port(), peer_port = free_udp_port();
  const std::string socket = (dir / "api.sock").string();
  std::ofstream(dir / "node.conf")
      << DaemonConfig{.data_dir = dir / "data",
                      .unix_socket = socket,
                      .proto_file = (dir / "net.proto").string()}.text()
      << "queue { type { type: \"net.Status\" roles { source_field: \"src\" destination_field: \"dest\" } } }\n"
      << "driver { name: \"udp\" modem_id: 1 restart_min_s: 0.2 restart_max_s: 0.5\n"
      << "  udp { listen: \"127.0.0.1:" << listen_port << "\" peers: \"127.0.0.1:" << peer_port << "\" } }\n"
      << "mac { name: \"fixed\" slot { src: 1 rate: 5 seconds: 1 } }\n";

  int blocker = bound_udp_socket(listen_port);  // the driver's port is taken
  int peer = bound_udp_socket(peer_port);
  ChildProcess daemon(ACOMMSD_BINARY, {"--config", (dir / "node.conf").string()}, (dir / "daemon").string());
  ASSERT_TRUE(wait_serving(daemon, socket)) << daemon.stderr_text();

  auto stub = api(socket);
  for (int battery : {71, 72, 73}) {
    grpc::ClientContext context;
    v1::SubmitRequest request;
    request.set_type("net.Status");
    request.set_json(R"({"src": 1, "dest": 0, "battery": )" + std::to_string(battery) + "}");
    v1::SubmitResponse response;
    grpc::Status status = stub->Submit(&context, request, &response);
    ASSERT_TRUE(status.ok()) << status.error_message();
  }
  // Two failures mean the supervisor's restart ran, met the taken port
  // again, and the daemon is still up to say so.
  auto driver_failures = [&] {
    grpc::ClientContext context;
    v1::LinkStatusResponse link;
    return stub->LinkStatus(&context, {}, &link).ok() ? link.driver().failures() : 0;
  };
  EXPECT_TRUE(wait_until([&] { return driver_failures() >= 2 || !daemon.running(); }, 20s))
      << "the driver never failed twice: " << daemon.stderr_text();
  EXPECT_TRUE(daemon.running());
  EXPECT_NE(daemon.stderr_text().find("restart"), std::string::npos) << daemon.stderr_text();
  {
    grpc::ClientContext context;
    v1::Status status;
    EXPECT_TRUE(stub->GetStatus(&context, {}, &status).ok()) << "the API serves while the driver is down";
  }

  ::close(blocker);  // the transport comes back
  dccl::Codec codec;
  codec.load((dir / "net.proto").string());
  std::set<int> batteries;
  auto deadline = std::chrono::steady_clock::now() + 20s;
  while (batteries.size() < 3 && std::chrono::steady_clock::now() < deadline) {
    pollfd waiting{peer, POLLIN, 0};
    if (::poll(&waiting, 1, 500) <= 0) continue;
    char buffer[65536];
    ssize_t n = ::recv(peer, buffer, sizeof(buffer), 0);
    v1::ModemTransmission transmission;
    if (n <= 0 || !transmission.ParseFromArray(buffer, static_cast<int>(n))) continue;
    if (transmission.type() != v1::ModemTransmission::DATA) continue;
    for (const std::string& frame : transmission.frame()) {
      if (frame.empty()) continue;
      for (const auto& message : codec.decode(frame)) {
        const auto* field = message->GetDescriptor()->FindFieldByName("battery");
        batteries.insert(message->GetReflection()->GetInt32(*message, field));
      }
    }
  }
  EXPECT_EQ(batteries, (std::set<int>{71, 72, 73})) << daemon.stderr_text();
  ::close(peer);
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.wait(15s), std::optional<int>(0)) << daemon.stderr_text();
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace acomms::testing
