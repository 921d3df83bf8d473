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
// Positions are numbered in the topside's received sequence: `acommsctl sub
// --resume FILE`, stopped and started again across the phases and cut off
// by the topside's kill, prints every position once; Subscribe `after: N`
// replays them.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "child_process.h"
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

  // `acommsctl sub acomms.telemetry.Position --resume FILE` on the topside.
  std::unique_ptr<ChildProcess> start_position_sub(int n) {
    return std::make_unique<ChildProcess>(
        ACOMMSCTL_BINARY,
        std::vector<std::string>{"--socket", net_.socket(2), "sub", "acomms.telemetry.Position", "--resume",
                                 (net_.dir() / "sub.cursor").string()},
        (net_.dir() / ("sub" + std::to_string(n))).string());
  }

  SimNetwork net_{"telemetry", kSlotSeconds};
  double t0_ = 0;
};

// (seq, sample time) of each line `acommsctl sub` printed.
std::vector<std::pair<int64_t, double>> printed_positions(const std::string& out) {
  static const std::regex time_field("\"time\":([-0-9.eE+]+)");
  static const std::regex seq_field("\"seq\":([0-9]+)\\}$");
  std::vector<std::pair<int64_t, double>> got;
  for (const std::string& line : lines_of(out)) {
    std::smatch time, seq;
    if (!std::regex_search(line, time, time_field) || !std::regex_search(line, seq, seq_field)) {
      ADD_FAILURE() << "not a Position line: " << line;
      continue;
    }
    got.emplace_back(std::stoll(seq[1]), std::stod(time[1]));
  }
  return got;
}

TEST_F(TelemetryTwoNode, TrackIsCompleteInOrderAndExactThroughLossAndKillsOfEachEnd) {
  std::vector<std::unique_ptr<ChildProcess>> subs;
  subs.push_back(start_position_sub(1));
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
  // The first reader stops (SIGTERM: a clean end) with the stream in flight.
  ASSERT_TRUE(wait_until([&] { return !subs[0]->stdout_text().empty(); }, 30s, 100ms)) << subs[0]->stderr_text();
  subs[0]->signal(SIGTERM);
  EXPECT_EQ(subs[0]->wait(10s), 0) << subs[0]->stderr_text();
  // 2. SIGKILL the vehicle with its stream in flight.
  RecordProperty("positions_at_vehicle_kill", track().positions_size());
  kill9_and_restart(1);
  feed_with_api(kMinute + 1, 2 * kMinute);
  ASSERT_TRUE(wait_for_track(kMinute + 20, 90s)) << net_.daemon(1).stderr_text();
  // A second reader resumes; the topside's kill below ends its stream.
  subs.push_back(start_position_sub(2));
  ASSERT_TRUE(wait_until([&] { return !subs[1]->stdout_text().empty(); }, 30s, 100ms)) << subs[1]->stderr_text();
  // 3. SIGKILL the topside with the stream in flight.
  RecordProperty("positions_at_topside_kill", track().positions_size());
  kill9_and_restart(2);
  EXPECT_TRUE(subs[1]->wait(10s).has_value()) << "the reader outlived its daemon";
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

  // The third reader resumes after the second's last line: the three
  // printed every position once, in increasing seq.
  subs.push_back(start_position_sub(3));
  auto printed = [&] {
    std::vector<std::pair<int64_t, double>> all_lines;
    for (const auto& sub : subs) {
      for (const auto& line : printed_positions(sub->stdout_text())) all_lines.push_back(line);
    }
    return all_lines;
  };
  ASSERT_TRUE(wait_until([&] { return printed().size() >= static_cast<size_t>(all); }, 30s, 200ms))
      << printed().size() << " of " << all << " printed\n"
      << subs[2]->stderr_text();
  subs[2]->signal(SIGTERM);
  EXPECT_EQ(subs[2]->wait(10s), 0) << subs[2]->stderr_text();
  const std::vector<std::pair<int64_t, double>> lines_printed = printed();
  ASSERT_EQ(lines_printed.size(), static_cast<size_t>(all));
  std::set<double> times;
  for (size_t i = 0; i < lines_printed.size(); ++i) {
    times.insert(lines_printed[i].second);
    if (i > 0) EXPECT_GT(lines_printed[i].first, lines_printed[i - 1].first) << i;
  }
  EXPECT_EQ(times.size(), static_cast<size_t>(all));
  EXPECT_EQ(*times.begin(), t0_);
  EXPECT_EQ(*times.rbegin(), t0_ + all - 1);
  RecordProperty("position_readers", static_cast<int>(subs.size()));

  // Subscribe `after: N` replays the positions after N, and only them.
  const int64_t seq_of_100th = lines_printed[99].first;
  StreamSubscriber replayed(net_.socket(2), "acomms.telemetry.Position", seq_of_100th);
  ASSERT_TRUE(replayed.wait_for([&](const auto& got) { return got.size() >= static_cast<size_t>(all - 100); }, 20s));
  const std::vector<v1::ReceivedMessage> got_replayed = replayed.received();
  ASSERT_EQ(got_replayed.size(), static_cast<size_t>(all - 100));
  for (size_t i = 0; i < got_replayed.size(); ++i) {
    EXPECT_EQ(got_replayed[i].seq(), lines_printed[100 + i].first) << i;
    telemetry::Position p;
    ASSERT_TRUE(p.ParseFromString(got_replayed[i].payload()));
    EXPECT_EQ(p.time(), lines_printed[100 + i].second) << i;
    EXPECT_EQ(got_replayed[i].src(), 1);
    EXPECT_EQ(got_replayed[i].dest(), 2);
  }
}

}  // namespace
}  // namespace acomms::testing
