// The map's transmission-loss section (cli/geov/tl_section.h) against a real
// acommsd: with an environment the picture is a PNG of the run towards the
// vehicle, from the daemon's own node's position when the map has one; it is
// reused while the vehicle stays put and run again when it moves (the
// daemon's pool counts the runs); a daemon without an environment, or one
// that cannot be reached, is a 503 naming the reason.
#include <gtest/gtest.h>

#include <fstream>

#include "acomms/v1/gram.grpc.pb.h"
#include "daemon_harness.h"
#include "geov/tl_section.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using cli::geov::SectionPicture;
using cli::geov::SectionRefusal;
using cli::geov::TlSection;

const char* const kEnvironment =
    "gram { base { title: \"test shelf\" frequency_hz: 10000 source_depth_m: 5 beam_count: 200\n"
    "  launch_angle_min_deg: -80 launch_angle_max_deg: 80 box_depth_m: 70 box_range_m: 1000\n"
    "  sound_speed { depth_m: 0 speed_mps: 1510 } sound_speed { depth_m: 60 speed_mps: 1500 }\n"
    "  bottom { kind: HALF_SPACE half_space { speed_mps: 1700 density_ratio: 1.9 } } } }\n";

telemetry::Position at(int32_t src, double x, double y, double depth) {
  telemetry::Position p;
  p.set_src(src);
  p.set_time(1000 + x);
  p.set_x(x);
  p.set_y(y);
  p.set_depth(depth);
  return p;
}

class GeovSection : public ::testing::Test {
 protected:
  void start(bool with_environment) {
    dir_ = fs::path("/tmp") / ("acomms-geov-section-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    socket_ = (dir_ / "api.sock").string();
    DaemonConfig{.data_dir = dir_ / "data", .unix_socket = socket_, .rest = with_environment ? kEnvironment : ""}
        .write(dir_ / "acommsd.conf");
    daemon_ = std::make_unique<ChildProcess>(ACOMMSD_BINARY, std::vector<std::string>{"--config", (dir_ / "acommsd.conf").string()},
                                             (dir_ / "acommsd").string());
    ASSERT_TRUE(wait_serving(*daemon_, socket_)) << daemon_->stderr_text();
  }
  void TearDown() override {
    daemon_.reset();
    if (!HasFailure() && !dir_.empty()) fs::remove_all(dir_);
  }
  cli::GlobalOptions options() const { return {.endpoint = socket_, .timeout_s = 1}; }
  uint64_t runs() {
    grpc::ClientContext context;
    v1::PoolStatusReply reply;
    EXPECT_TRUE(v1::Gram::NewStub(grpc::CreateChannel("unix:" + socket_, grpc::InsecureChannelCredentials()))
                    ->PoolStatus(&context, v1::PoolStatusRequest(), &reply)
                    .ok());
    return reply.completed();
  }
  int32_t own_id() {
    grpc::ClientContext context;
    v1::LinkStatusResponse link;
    EXPECT_TRUE(api(socket_)->LinkStatus(&context, v1::LinkStatusRequest(), &link).ok());
    return static_cast<int32_t>(link.modem_id());
  }

  fs::path dir_;
  std::string socket_;
  std::unique_ptr<ChildProcess> daemon_;
  cli::geov::Fleet fleet_;
};

TEST_F(GeovSection, TheDaemonsModelDrawsItOnceWhileTheVehicleStaysAndAgainWhenItMoves) {
  start(true);
  // The buoy (the daemon's own node) 40 m east of the datum; the vehicle
  // 100 m east: 60 m apart.
  fleet_.add_positions({at(own_id(), 40, 0, 5)});
  TlSection sections(options(), fleet_);
  const uint64_t before = runs();
  const SectionPicture first = sections.picture(at(2, 100, 0, 20));
  EXPECT_EQ(first.png.substr(0, 8), "\x89PNG\r\n\x1a\n");
  EXPECT_GT(first.png.size(), 10000u);
  EXPECT_DOUBLE_EQ(first.range_m, 60);
  EXPECT_EQ(runs(), before + 1);
  // About where it was (0.5 m): the same picture, no new run.
  const SectionPicture again = sections.picture(at(2, 100.5, 0, 20.5));
  EXPECT_TRUE(again.png == first.png) << "the picture was drawn again";
  EXPECT_EQ(runs(), before + 1);
  // Moved 300 m: a longer section, a new run, another picture.
  const SectionPicture moved = sections.picture(at(2, 400, 0, 20));
  EXPECT_DOUBLE_EQ(moved.range_m, 360);
  EXPECT_TRUE(moved.png != first.png) << "the same picture after the move";
  EXPECT_EQ(runs(), before + 2);
}

TEST_F(GeovSection, WithoutAnEnvironmentOrADaemonTheReasonIsA503) {
  start(false);
  TlSection sections(options(), fleet_);
  try {
    sections.picture(at(2, 100, 0, 20));
    FAIL() << "a picture without an environment";
  } catch (const SectionRefusal& r) {
    EXPECT_EQ(r.status, 503);
    EXPECT_NE(r.text.find("the daemon holds no environment"), std::string::npos) << r.text;
  }
  daemon_.reset();
  try {
    sections.picture(at(2, 300, 0, 20));
    FAIL() << "a picture without a daemon";
  } catch (const SectionRefusal& r) {
    EXPECT_EQ(r.status, 503);
    EXPECT_NE(r.text.find("cannot reach acommsd"), std::string::npos) << r.text;
  }
}

}  // namespace
}  // namespace acomms::testing
