// Position telemetry between two real acommsd processes (vehicle 1,
// topside 2) on the loopback sim channel, with loss, and a SIGKILL of each
// end while the stream runs:
//
//  1. acommsctl nav feeds the vehicle a minute of track (tau 1 s); the
//     topside reconstructs it while 25% of transmissions are lost.
//  2. The vehicle is SIGKILLed mid-stream (messages still queued) and
//     restarted; a second minute follows through the API.
//  3. The topside is SIGKILLed mid-stream and restarted; a third minute.
// The topside's track (acommsctl track --csv and the Track call) is then
// every sample, in order, each exactly the vehicle's position on the 1 m
// grid, with at most one full transmission besides the first per restart;
// subscribers saw the positions as acomms.telemetry.Position.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

#include "daemon_harness.h"
#include "sim_network.h"
#include "stream_subscriber.h"
#include "util/seconds.h"

namespace acomms::testing {
namespace {

using namespace std::chrono_literals;

// A 2.5 s slot at rate 5 carries one 256-byte frame, about 36 messages: a
// minute of track takes two of the vehicle's slots, so each kill lands with
// part of it still queued.
constexpr double kSlotSeconds = 2.5;
constexpr int kMinute = 60;

// The vehicle's track: a lawnmower-like run with a turn and a yo-yo in
// depth, within 300 m of the topside (the MAC's range guard is 400 m), at
// local times t0 + s for s in [0, 180].
struct Point {
  double x, y, depth;
};
Point track_at(double s) {
  Point p;
  // Fractions chosen so that no whole-second sample lies on a half metre,
  // where rounding to the grid would hang on the last bit.
  if (s < 100) {
    p.x = 20.2 + 1.5 * s;
    p.y = 10.05;
  } else {  // a turn, then mostly north
    p.x = 170.05 + 0.3 * (s - 100);
    p.y = 10.05 + 1.4 * (s - 100);
  }
  p.depth = 20 + 10 * std::sin(s / 15.0);
  return p;
}

class TelemetryTwoNode : public ::testing::Test {
 protected:
  void SetUp() override {
    for (int id : {1, 2}) {
      // No periodic full within the test: every full is the start's or a restart's.
      net_.write_config(id, {.sim = "loss_probability: 0.25 seed: " + std::to_string(40 + id),
                             .rest = std::string("telemetry { tau_s: 1 full_every: 1000 ttl_s: 600") +
                                     (id == 1 ? " receiver: 2" : "") + " }\n",
                             .example_messages = false});
    }
    net_.start(1);
    net_.start(2);
    // Sample times on the whole second, today (a full codes the time of day).
    t0_ = std::floor(util::unix_seconds_now());
  }
  void TearDown() override { net_.stop(); }

  void kill9_and_restart(int id) {
    net_.daemon(id).signal(SIGKILL);
    net_.daemon(id).wait(10s);
    net_.start(id);
  }

  // Fixes every 0.5 s for s in [from, to].
  std::vector<std::pair<double, Point>> fixes(int from, int to) const {
    std::vector<std::pair<double, Point>> out;
    for (double s = from; s <= to; s += 0.5) out.emplace_back(t0_ + s, track_at(s));
    return out;
  }

  void feed_with_acommsctl(int from, int to) {
    std::ostringstream csv;
    csv.precision(12);
    csv << "time,x,y,depth\n";
    for (const auto& [t, p] : fixes(from, to)) csv << t << ',' << p.x << ',' << p.y << ',' << p.depth << '\n';
    RunResult result = run_with_input(ACOMMSCTL_BINARY, {"--socket", net_.socket(1), "nav"}, (net_.dir() / "nav").string(),
                                      csv.str());
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find(std::to_string(to - from + 1) + " telemetry messages queued"), std::string::npos)
        << result.out;
  }

  void feed_with_api(int from, int to) {
    grpc::ClientContext context;
    v1::SubmitNavigationResponse response;
    auto stub = api(net_.socket(1));
    auto writer = stub->SubmitNavigation(&context, &response);
    for (const auto& [t, p] : fixes(from, to)) {
      v1::NavigationFix fix;
      fix.set_time(t);
      fix.mutable_local()->set_x(p.x);
      fix.mutable_local()->set_y(p.y);
      fix.set_depth(p.depth);
      ASSERT_TRUE(writer->Write(fix));
    }
    writer->WritesDone();
    grpc::Status status = writer->Finish();
    ASSERT_TRUE(status.ok()) << status.error_message();
    EXPECT_EQ(response.messages_queued(), static_cast<uint64_t>(to - from + 1));
  }

  v1::TrackResponse track() {
    grpc::ClientContext context;
    v1::TrackRequest request;
    request.set_src(1);
    v1::TrackResponse response;
    grpc::Status status = api(net_.socket(2))->Track(&context, request, &response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return response;
  }

  bool wait_for_track(int positions, std::chrono::seconds timeout) {
    return wait_until([&] { return track().positions_size() >= positions; }, timeout, 200ms);
  }

  SimNetwork net_{"telemetry", kSlotSeconds};
  double t0_ = 0;
};

TEST_F(TelemetryTwoNode, TrackIsCompleteInOrderAndExactThroughLossAndKillsOfEachEnd) {
  {
    StreamSubscriber positions(net_.socket(2), "acomms.telemetry.Position");
    // 1. A minute through acommsctl nav.
    feed_with_acommsctl(0, kMinute);
    // Mid-stream: some of it is across, some still queued at the vehicle.
    ASSERT_TRUE(wait_for_track(10, 60s)) << net_.daemon(1).stderr_text() << net_.daemon(2).stderr_text();
    ASSERT_TRUE(positions.wait_for([](const auto& got) { return !got.empty(); }, 10s));
    const v1::ReceivedMessage first = positions.received().front();
    EXPECT_EQ(first.src(), 1);
    telemetry::Position p;
    ASSERT_TRUE(p.ParseFromString(first.payload()));
    EXPECT_EQ(p.time(), t0_);
    EXPECT_EQ(p.x(), std::round(track_at(0).x));
    EXPECT_TRUE(p.full());
  }
  // 2. SIGKILL the vehicle with its stream in flight.
  RecordProperty("positions_at_vehicle_kill", track().positions_size());
  kill9_and_restart(1);
  feed_with_api(kMinute + 1, 2 * kMinute);
  ASSERT_TRUE(wait_for_track(kMinute + 20, 90s)) << net_.daemon(1).stderr_text();
  // 3. SIGKILL the topside with the stream in flight.
  RecordProperty("positions_at_topside_kill", track().positions_size());
  kill9_and_restart(2);
  feed_with_api(2 * kMinute + 1, 3 * kMinute);
  const int all = 3 * kMinute + 1;
  ASSERT_TRUE(wait_for_track(all, 120s)) << "topside has " << track().positions_size() << " of " << all << "\n"
                                         << net_.daemon(2).stderr_text();

  const v1::TrackResponse got = track();
  ASSERT_EQ(got.positions_size(), all);
  int fulls = 0;
  for (int s = 0; s < all; ++s) {
    const telemetry::Position& p = got.positions(s);
    const Point want = track_at(s);
    EXPECT_EQ(p.src(), 1);
    EXPECT_EQ(p.time(), t0_ + s) << s;
    EXPECT_EQ(p.x(), std::round(want.x)) << s;
    EXPECT_EQ(p.y(), std::round(want.y)) << s;
    EXPECT_EQ(p.z(), std::round(-want.depth)) << s;
    EXPECT_EQ(p.depth(), -p.z()) << s;
    fulls += p.full() ? 1 : 0;
  }
  // The start's, and one for the vehicle's restart; the topside's restart
  // costs none (it continues from its store and event log).
  EXPECT_LE(fulls, 3);
  EXPECT_GE(fulls, 2);
  RecordProperty("fulls", fulls);

  // acommsctl track prints the same track.
  RunResult csv = run(ACOMMSCTL_BINARY, {"--socket", net_.socket(2), "track", "1", "--csv"}, (net_.dir() / "track").string());
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  std::vector<std::string> lines = lines_of(csv.out);
  ASSERT_EQ(lines.size(), static_cast<size_t>(all + 1));
  EXPECT_EQ(lines[0], "time,x,y,z,lat,lon,depth,full");
}

}  // namespace
}  // namespace acomms::testing
