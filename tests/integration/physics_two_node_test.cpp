// Two real acommsd processes on the loopback sim channel with physics
// (driver.sim.physics): the vehicle's depth decides what gets through, in
// the direction the model predicts.
//
// The water (written by the test): 100 m, sound speed falling from 1530 m/s
// at the surface to 1470 m/s at the bottom (strong downward refraction) over
// a bottom that reflects nothing, 2 kHz. The topside's modem is at 60 m;
// the vehicle 1000 m away. The model gives 60 dB at 60 m and 75.6 dB at 5 m
// (checked here on the model itself), and the noise level is set so that
// the PSK curve's midpoint (14 dB) lies between: at 5 m a packet decodes
// with p ≈ 5e-4, at 60 m with p ≈ 0.9997.
//
// One vehicle daemon runs throughout; only its navigation input moves it.
// Its config puts it at 600 m and 60 m deep (lit), but the first fix
// (SubmitNavigation, local x/y as acommsctl nav sends them) puts it 1000 m
// away at 5 m before anything is queued: its Status is sent again and again
// and never arrives. A second fix takes it down to 60 m, and the same queued
// Status arrives, with the modelled SNR for 1000 m and 60 m in its link
// figures (the range there shows the fix, not the config, placed it).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>

#include "acomms/v1/gram.grpc.pb.h"
#include "daemon_harness.h"
#include "gram/bellhop_import.h"
#include "gram/tl_lookup.h"
#include "gram/transmission_loss.h"
#include "stream_subscriber.h"
#include "util/seconds.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr double kNoiseDb = 108;  // 190 − 68 − 14: the PSK midpoint at 68 dB TL
constexpr double kRange = 1000;

constexpr const char* kEnv = R"('physics test: downward refraction over an absorbing bottom, 2 kHz'
2000
1
'CVW'
0 0.0 100
  0.0 1530.0 /
100.0 1470.0 /
'A' 0.0
100.0 1470.0 0.0 1.0 0.0 0.0 /
1
60 /
1
50 /
1
1 /
'I'
0
-89 89 /
0 101 1.1
)";

class PhysicsTwoNode : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path("/tmp") / ("acomms-physics-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "water.env") << kEnv;
    port_[1] = free_udp_port();
    port_[2] = free_udp_port();
  }
  void TearDown() override {
    for (auto& [id, daemon] : daemons_) stop(id);
    fs::remove_all(dir_);
  }

  static std::string name(int id) { return id == 1 ? "vehicle" : "topside"; }
  std::string socket(int id) const { return (dir_ / (name(id) + ".sock")).string(); }

  void start(int id, double x, double depth) {
    const fs::path conf = dir_ / (name(id) + ".conf");
    std::ofstream config(conf);
    config << DaemonConfig{.data_dir = dir_ / name(id),
                           .unix_socket = socket(id),
                           .proto_file = ACOMMS_SOURCE_DIR "/examples/messages.proto"}.text()
           << "driver { name: \"sim\" modem_id: " << id << " sim { position { x: " << x << " z: " << -depth
           << " } listen: \"127.0.0.1:" << port_[id] << "\" peers: \"127.0.0.1:" << port_[3 - id] << "\""
           << " physics { env_file: \"" << (dir_ / "water.env").string() << "\" noise_level_db: " << kNoiseDb
           << " max_range_m: 1200 range_step_m: 20 depth_step_m: 5 } } }\n"
           << "mac { name: \"fixed\" slot { src: 1 rate: 5 seconds: 4 } slot { src: 2 rate: 5 seconds: 4 }"
           << " max_range_m: 1200 }\n"
           << "queue {\n"
           << "  type { type: \"example.Status\" policy { max_queue: 100 ttl_s: 600 }\n"
           << "         roles { source_field: \"src\" destination_field: \"dest\" timestamp_field: \"time\" } }\n"
           << "}\n";
    config.close();
    daemons_[id] = std::make_unique<ChildProcess>(ACOMMSD_BINARY, std::vector<std::string>{"--config", conf.string()},
                                                  dir_.string());
    ASSERT_TRUE(wait_serving(*daemons_[id], socket(id))) << daemons_[id]->stderr_text();
  }

  void stop(int id) {
    auto& daemon = daemons_[id];
    if (!daemon || !daemon->running()) return;
    daemon->signal(SIGTERM);
    EXPECT_EQ(daemon->wait(15s), std::optional<int>(0)) << name(id) << ":\n" << daemon->stderr_text();
  }

  // A navigation fix for the vehicle (local metres from the telemetry
  // datum; no telemetry config needed), answered once the daemon took it.
  void navigate_vehicle(double x, double depth) {
    // Fixes must move time forward; the wall clock may not have.
    fix_time_ = std::max(fix_time_ + 1, util::unix_seconds_now());
    grpc::ClientContext context;
    v1::SubmitNavigationResponse response;
    auto writer = api(socket(1))->SubmitNavigation(&context, &response);
    v1::NavigationFix fix;
    fix.set_time(fix_time_);
    fix.mutable_local()->set_x(x);
    fix.mutable_local()->set_y(0);
    fix.set_depth(depth);
    ASSERT_TRUE(writer->Write(fix));
    writer->WritesDone();
    grpc::Status status = writer->Finish();
    ASSERT_TRUE(status.ok()) << status.error_message();
    ASSERT_EQ(response.accepted_fixes(), 1u);
  }

  int64_t submit_status() {
    grpc::ClientContext context;
    v1::SubmitRequest request;
    request.set_type("example.Status");
    request.set_json(R"({"dest": 2, "x": 1000, "y": 0, "depth": 5, "seq": 1})");
    v1::SubmitResponse response;
    grpc::Status status = api(socket(1))->Submit(&context, request, &response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return status.ok() ? response.message_id() : -1;
  }

  int times_sent(int64_t message_id) {
    grpc::ClientContext context;
    v1::EventsRequest request;
    request.set_message_id(message_id);
    v1::EventsResponse response;
    EXPECT_TRUE(api(socket(1))->Events(&context, request, &response).ok());
    int sent = 0;
    for (const auto& event : response.events()) sent += event.kind() == "sent";
    return sent;
  }

  // The model's TL from the topside (the source) to the vehicle, on the
  // grid the driver uses.
  double model_tl(double depth) const {
    gram::Environment env = gram::import_bellhop_env_file((dir_ / "water.env").string()).environment;
    env.clear_receiver_depth_m();
    env.clear_receiver_range_m();
    for (int i = 0; i <= 20; ++i) env.add_receiver_depth_m(i * 5.0);
    for (int i = 0; i <= 60; ++i) env.add_receiver_range_m(i * 20.0);
    env.set_box_range_m(1220);
    env.set_source_depth_m(60);
    return gram::tl_at(gram::compute_transmission_loss(env, {1}), kRange, depth);
  }

  fs::path dir_;
  std::map<int, int> port_;
  std::map<int, std::unique_ptr<ChildProcess>> daemons_;
  double fix_time_ = 0;
};

TEST_F(PhysicsTwoNode, AtTheDepthTheModelShadowsNothingArrivesAndAtTheLitDepthItDoes) {
  const double tl_shadow = model_tl(5), tl_lit = model_tl(60);
  ASSERT_GT(tl_shadow, 190 - kNoiseDb - 14 + 5) << "the model no longer shadows 5 m: the test's premise is gone";
  ASSERT_LT(tl_lit, 190 - kNoiseDb - 14 - 5) << "the model no longer lights 60 m";

  start(2, 0, 60);
  // Lit where the config puts it: only the navigation can shadow it.
  start(1, 600, 60);
  StreamSubscriber topside(socket(2), "example.Status");
  navigate_vehicle(kRange, 5);
  const int64_t id = submit_status();
  ASSERT_GT(id, 0);
  // At 5 m: sent in four vehicle slots, never heard (p ≈ 5e-4 each).
  // (An arrival ends the wait too: a message heard is not sent again.)
  ASSERT_TRUE(wait_until([&] { return times_sent(id) >= 4 || !topside.received().empty(); }, 90s, 200ms))
      << daemons_[1]->stderr_text();
  ASSERT_TRUE(topside.received().empty()) << "heard from the shadow: " << topside.received().front().DebugString();

  // The same running vehicle dives to 60 m: the same Status arrives.
  navigate_vehicle(kRange, 60);
  ASSERT_TRUE(topside.wait_for([](const auto& got) { return !got.empty(); }, 60s)) << daemons_[1]->stderr_text();
  EXPECT_TRUE(daemons_[1]->running()) << daemons_[1]->stderr_text();
  const v1::ReceivedMessage status = topside.received().front();
  EXPECT_EQ(status.src(), 1);
  ASSERT_TRUE(status.link().has_snr_in_db()) << status.DebugString();
  // Where the fix put it, not the config.
  EXPECT_NE(status.link().link_quality().find("range_m=1000.0 "), std::string::npos) << status.DebugString();
  EXPECT_NEAR(status.link().range_m(), 1000.0, 0.05) << status.DebugString();
  // The topside's grid has itself (60 m) as the source: the same model.
  EXPECT_NEAR(status.link().snr_in_db(), 190 - tl_lit - kNoiseDb, 1e-6);
  // That grid was run by the daemon's GRAM pool, not a thread of the driver's.
  auto gram = v1::Gram::NewStub(grpc::CreateChannel("unix:" + socket(2), grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + 10s);
  v1::PoolStatusReply pool;
  ASSERT_TRUE(gram->PoolStatus(&context, v1::PoolStatusRequest(), &pool).ok());
  EXPECT_GE(pool.completed(), 1u);
}

}  // namespace
}  // namespace acomms::testing
