// The map server's playback periods and its environment picture, end to
// end over loopback: a chosen period is cut to the positions held, one
// outside them or holding more than --max-period is refused with both
// spans or the bound named; /api/section answers the picture of the
// vehicle's last position, or the reason there is none (unknown vehicle,
// no model to ask, the model's own refusal) as a status and one line.
#include <gtest/gtest.h>

#include <thread>

#include "geov/map_site.h"
#include "http_client.h"

namespace acomms::cli::geov {
namespace {

using testing::body_of;
using testing::get;
using testing::status_of;

telemetry::Position at(int32_t src, double t, double x, double y, double depth = 12.5) {
  telemetry::Position p;
  p.set_src(src);
  p.set_time(t);
  p.set_x(x);
  p.set_y(y);
  p.set_depth(depth);
  p.set_lat(41.5 + y / 111320);
  p.set_lon(-70.6 + x / 83000);
  return p;
}

class PeriodAndSectionTest : public ::testing::Test {
 protected:
  void start(SiteOptions options = {}) {
    site_ = std::make_unique<MapSite>(fleet_, options);
    server_ = std::make_unique<HttpServer>(HttpServerOptions{.listen = "127.0.0.1:0"},
                                           [this](const HttpRequest& r, HttpResponder& w) { site_->handle(r, w); });
    runner_ = std::thread([this] { server_->run(); });
  }
  void TearDown() override {
    fleet_.close();
    if (server_) server_->stop();
    if (runner_.joinable()) runner_.join();
  }
  int port() const { return server_->port(); }

  Fleet fleet_;
  std::unique_ptr<MapSite> site_;
  std::unique_ptr<HttpServer> server_;
  std::thread runner_;
};

TEST_F(PeriodAndSectionTest, APeriodIsCutToThePositionsHeldAndAllOfThemWithoutOne) {
  fleet_.add_positions({at(1, 1000, 0, 0), at(1, 1010, 1, 0), at(1, 1020, 2, 0), at(2, 1005, 9, 9)});
  start();
  std::string r = body_of(get(port(), "/api/history?from=990&to=1012"));
  EXPECT_EQ(r.rfind("{\"from\":1000,\"to\":1012,\"vehicles\":[{\"src\":1,\"track\":[[1000,", 0), 0u) << r;
  EXPECT_EQ(r.find("[1020,"), std::string::npos) << r;
  r = body_of(get(port(), "/api/history"));
  EXPECT_EQ(r.rfind("{\"from\":1000,\"to\":1020,", 0), 0u) << r;
  EXPECT_NE(r.find("[1020,"), std::string::npos) << r;
  r = body_of(get(port(), "/api/history?src=2"));
  EXPECT_EQ(r.rfind("{\"from\":1005,\"to\":1005,", 0), 0u) << r;
}

TEST_F(PeriodAndSectionTest, APeriodOutsideThePositionsHeldIsRefusedNamingBoth) {
  fleet_.add_positions({at(1, 1000, 0, 0), at(1, 1020, 2, 0)});
  start();
  for (const char* query : {"from=2000&to=3000", "from=10&to=999", "to=999"}) {
    const std::string r = get(port(), std::string("/api/history?") + query);
    EXPECT_EQ(status_of(r), 400) << query;
    EXPECT_NE(body_of(r).find("holds no positions: those held run from 1970-01-01T00:16:40Z to 1970-01-01T00:17:00Z"),
              std::string::npos)
        << r;
  }
  EXPECT_NE(body_of(get(port(), "/api/history?to=999")).find("the period the beginning to"), std::string::npos);
  EXPECT_EQ(status_of(get(port(), "/kml/history.kml?from=2000&to=3000")), 400);
  // End before start is named before anything else.
  EXPECT_NE(body_of(get(port(), "/api/history?from=1020&to=1000")).find("from (1020) is after to (1000)"),
            std::string::npos);
}

TEST_F(PeriodAndSectionTest, APeriodHoldingMoreThanTheBoundIsRefusedNamingIt) {
  fleet_.add_positions({at(1, 0 + 1e6, 0, 0), at(1, 7200 + 1e6, 1, 0), at(1, 14400 + 1e6, 2, 0)});
  SiteOptions options;
  options.max_period_s = 3 * 3600;
  start(options);
  std::string r = get(port(), "/api/history?from=0");
  EXPECT_EQ(status_of(r), 400);
  EXPECT_NE(body_of(r).find("the period holds 4 h of positions; at most 3 h at once (--max-period)"), std::string::npos)
      << r;
  EXPECT_EQ(status_of(get(port(), "/kml/history.kml?from=0")), 400);
  // No period chosen (a saved Google Earth link): the newest 3 h, not a
  // refusal once the positions held outgrow the bound.
  r = get(port(), "/api/history");
  EXPECT_EQ(status_of(r), 200) << r;
  EXPECT_EQ(body_of(r).rfind("{\"from\":1003600,\"to\":1014400,", 0), 0u) << r;
  EXPECT_EQ(status_of(get(port(), "/kml/history.kml")), 200) << "served, not refused as too long";
  // Within the bound: served, even when the period asked for is longer
  // than the positions it holds.
  r = get(port(), "/api/history?from=" + std::to_string(int(1e6) + 3600) + "&to=" + std::to_string(int(1e6) + 100000));
  EXPECT_EQ(status_of(r), 200) << r;
  EXPECT_NE(body_of(r).find("\"to\":1014400"), std::string::npos) << r;
}

TEST_F(PeriodAndSectionTest, NoPositionsYetRefusesAChosenPeriod) {
  start();
  EXPECT_EQ(status_of(get(port(), "/api/history")), 200);
  const std::string r = get(port(), "/api/history?from=-10m");
  EXPECT_EQ(status_of(r), 400);
  EXPECT_NE(body_of(r).find("no positions held yet"), std::string::npos) << r;
}

TEST_F(PeriodAndSectionTest, TheSectionIsThePictureOfTheVehiclesLastPosition) {
  fleet_.add_positions({at(2, 1000, 30, 40, 15), at(2, 1001, 60, 80, 17), at(4, 1000, 0, 0)});
  std::vector<telemetry::Position> asked;
  SiteOptions options;
  options.section = [&](const telemetry::Position& p) {
    asked.push_back(p);
    if (p.src() == 4) throw SectionRefusal{503, "the daemon holds no environment"};
    return SectionPicture{"\x89PNG-of-node-2", 100.0};
  };
  start(options);
  std::string r = get(port(), "/api/section?src=2");
  EXPECT_EQ(status_of(r), 200) << r;
  EXPECT_NE(r.find("Content-Type: image/png\r\n"), std::string::npos);
  EXPECT_NE(r.find("X-Acomms-Range-M: 100\r\n"), std::string::npos);
  EXPECT_EQ(body_of(r), "\x89PNG-of-node-2");
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0].time(), 1001);
  EXPECT_EQ(asked[0].depth(), 17);
  r = get(port(), "/api/section?src=4");
  EXPECT_EQ(status_of(r), 503);
  EXPECT_EQ(body_of(r), "the daemon holds no environment\n");
  r = get(port(), "/api/section?src=9");
  EXPECT_EQ(status_of(r), 404);
  EXPECT_NE(body_of(r).find("no vehicle 9 (vehicles with positions: 2, 4)"), std::string::npos) << r;
  r = get(port(), "/api/section");
  EXPECT_EQ(status_of(r), 400);
  EXPECT_NE(body_of(r).find("src: give the vehicle's modem id"), std::string::npos) << r;
  EXPECT_EQ(asked.size(), 2u);
}

TEST_F(PeriodAndSectionTest, WithoutAModelToAskTheSectionIs503) {
  fleet_.add_positions({at(2, 1000, 30, 40)});
  start();
  const std::string r = get(port(), "/api/section?src=2");
  EXPECT_EQ(status_of(r), 503);
  EXPECT_NE(body_of(r).find("no environment"), std::string::npos) << r;
}

}  // namespace
}  // namespace acomms::cli::geov
