// A real acommsd holding two links (two udp drivers, each under its own
// supervisor): with link "a"'s port held by someone else its driver keeps
// failing, while link "b" sends every queued message; LinkStatus reports
// each link by name (the first one's in the old top-level fields); a link
// can be disabled and enabled by name (SetLinkEnabled), and an unknown
// name is NOT_FOUND naming the node's links.

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
#include "daemon_harness.h"
#include "dccl/codec.h"
#include "net_status_proto.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

std::string udp_link(const std::string& name, int listen, int peer) {
  return "link { name: \"" + name + "\" driver { name: \"udp\" modem_id: 1 restart_min_s: 0.2 restart_max_s: 0.5\n" +
         "  udp { listen: \"127.0.0.1:" + std::to_string(listen) + "\" peers: \"127.0.0.1:" + std::to_string(peer) +
         "\" } }\n  mac { name: \"fixed\" slot { src: 1 rate: 5 seconds: 1 } } }\n";
}

v1::LinkStatusResponse link_status(v1::Acomms::Stub& stub, const std::string& name = "") {
  grpc::ClientContext context;
  v1::LinkStatusRequest request;
  request.set_link(name);
  v1::LinkStatusResponse response;
  EXPECT_TRUE(stub.LinkStatus(&context, request, &response).ok());
  return response;
}

TEST(SeveralLinks, FailingDriverOnOneLinkLeavesTheOtherSending) {
  fs::path dir = fs::path("/tmp") / ("acomms-links-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "net.proto") << kNetStatusProto;
  const int a_listen = free_udp_port(), a_peer = free_udp_port();
  const int b_listen = free_udp_port(), b_peer = free_udp_port();
  const std::string socket = (dir / "api.sock").string();
  std::ofstream(dir / "node.conf")
      << DaemonConfig{.data_dir = dir / "data", .unix_socket = socket, .proto_file = (dir / "net.proto").string()}
             .text()
      << "queue { type { type: \"net.Status\" roles { source_field: \"src\" destination_field: \"dest\" } } }\n"
      << udp_link("a", a_listen, a_peer) << udp_link("b", b_listen, b_peer);

  int blocker = bound_udp_socket(a_listen);  // link a's driver cannot open its port
  int peer = bound_udp_socket(b_peer);
  ChildProcess daemon(ACOMMSD_BINARY, {"--config", (dir / "node.conf").string()}, (dir / "daemon").string());
  ASSERT_TRUE(wait_serving(daemon, socket)) << daemon.stderr_text();
  auto stub = api(socket);

  EXPECT_TRUE(wait_until([&] { return link_status(*stub, "a").driver().failures() >= 2; }, 20s))
      << daemon.stderr_text();
  for (int battery : {81, 82, 83}) {
    grpc::ClientContext context;
    v1::SubmitRequest request;
    request.set_type("net.Status");
    request.set_json(R"({"src": 1, "dest": 0, "battery": )" + std::to_string(battery) + "}");
    v1::SubmitResponse response;
    ASSERT_TRUE(stub->Submit(&context, request, &response).ok());
  }
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
    for (const std::string& frame : transmission.frame()) {
      if (frame.empty()) continue;
      for (const auto& message : codec.decode(frame)) {
        batteries.insert(message->GetReflection()->GetInt32(*message, message->GetDescriptor()->FindFieldByName("battery")));
      }
    }
  }
  EXPECT_EQ(batteries, (std::set<int>{81, 82, 83})) << "link b did not carry them: " << daemon.stderr_text();

  v1::LinkStatusResponse all = link_status(*stub);
  ASSERT_EQ(all.links_size(), 2);
  EXPECT_EQ(all.name(), "a") << "the top-level fields are the first link's";
  EXPECT_EQ(all.links(0).name(), "a");
  EXPECT_EQ(all.links(1).name(), "b");
  EXPECT_EQ(all.links(0).driver().state(), "restarting");
  EXPECT_EQ(all.links(1).driver().state(), "running");
  EXPECT_EQ(all.links(1).driver().failures(), 0u) << "link a's failures touched link b";
  EXPECT_GT(all.links(1).counters().transmissions_sent(), 0u);
  EXPECT_EQ(all.links(0).counters().transmissions_sent(), 0u);

  {
    grpc::ClientContext context;
    v1::SetLinkEnabledRequest request;
    request.set_link("b");
    request.set_enabled(false);
    v1::SetLinkEnabledResponse response;
    ASSERT_TRUE(stub->SetLinkEnabled(&context, request, &response).ok());
    EXPECT_FALSE(response.enabled());
  }
  v1::LinkStatusResponse b = link_status(*stub, "b");
  EXPECT_FALSE(b.enabled());
  EXPECT_EQ(b.driver().state(), "stopped");
  ASSERT_EQ(b.links_size(), 1);
  {
    grpc::ClientContext context;
    v1::SetLinkEnabledRequest request;
    request.set_link("iridium");
    request.set_enabled(true);
    v1::SetLinkEnabledResponse response;
    grpc::Status status = stub->SetLinkEnabled(&context, request, &response);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
    EXPECT_NE(status.error_message().find("no link \"iridium\" (this node's links: \"a\", \"b\")"), std::string::npos)
        << status.error_message();
  }
  {
    grpc::ClientContext context;
    v1::SetLinkEnabledRequest request;
    request.set_link("b");
    request.set_enabled(true);
    v1::SetLinkEnabledResponse response;
    ASSERT_TRUE(stub->SetLinkEnabled(&context, request, &response).ok());
  }
  EXPECT_TRUE(wait_until([&] { return link_status(*stub, "b").driver().state() == "running"; }, 10s));

  ::close(blocker);
  ::close(peer);
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.wait(15s), std::optional<int>(0)) << daemon.stderr_text();
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace acomms::testing
