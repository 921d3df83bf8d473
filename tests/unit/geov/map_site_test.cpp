// The map server end to end over loopback sockets: a Fleet filled by the
// test, the real HttpServer and MapSite. What each page answers, what bad
// requests get (status and reason), the token, the bounds on connections,
// and the event stream: live updates, resumption without a gap, many
// viewers, and a viewer that leaves.
#include <gtest/gtest.h>

#include <sqlite3.h>

#include <thread>

#include "geov/assets.h"
#include "geov/map_site.h"
#include "http_client.h"
#include "wait_until.h"

namespace acomms::cli::geov {
namespace {

using namespace std::chrono_literals;
using testing::body_of;
using testing::get;
using testing::RawHttp;
using testing::status_of;
using acomms::testing::wait_until;

telemetry::Position at(int32_t src, double t, double x, double y, bool latlon = true) {
  telemetry::Position p;
  p.set_src(src);
  p.set_time(t);
  p.set_x(x);
  p.set_y(y);
  p.set_depth(12.5);
  p.set_z(-12.5);
  if (latlon) {
    p.set_lat(41.5 + y / 111320);
    p.set_lon(-70.6 + x / 83000);
  }
  return p;
}

class MapSiteTest : public ::testing::Test {
 protected:
  void start(SiteOptions options = {}, int max_connections = 64, double read_timeout_s = 10) {
    options.heartbeat_s = 0.2;
    site_ = std::make_unique<MapSite>(fleet_, options);
    server_ = std::make_unique<HttpServer>(HttpServerOptions{.listen = "127.0.0.1:0",
                                                             .max_connections = max_connections,
                                                             .read_timeout_s = read_timeout_s},
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

TEST_F(MapSiteTest, ServesTheBuiltInPageAndLeafletAndNothingFromDisk) {
  start();
  const std::string page = get(port(), "/");
  EXPECT_EQ(status_of(page), 200);
  EXPECT_NE(page.find("Content-Type: text/html; charset=utf-8"), std::string::npos);
  EXPECT_NE(body_of(page).find("<script src=\"/leaflet.js\">"), std::string::npos);
  const std::string leaflet = get(port(), "/leaflet.js");
  EXPECT_EQ(status_of(leaflet), 200);
  EXPECT_EQ(body_of(leaflet), std::string(find_asset("/leaflet.js")->bytes));
  EXPECT_NE(body_of(leaflet).find("Leaflet"), std::string::npos);
  for (const char* path : {"/etc/passwd", "/../../etc/passwd", "/%2e%2e/etc/passwd", "/images/../leaflet.js",
                           "/leaflet.js/", "/index.html"}) {
    const std::string response = get(port(), path);
    EXPECT_EQ(status_of(response), 404) << path;
    EXPECT_NE(body_of(response).find("no such page"), std::string::npos) << path;
  }
}

TEST_F(MapSiteTest, BadRequestsGetTheirStatusAndReason) {
  start();
  auto raw = [&](const std::string& bytes) {
    RawHttp http(port());
    http.send(bytes);
    return http.read_all();
  };
  EXPECT_EQ(status_of(raw("POST / HTTP/1.1\r\n\r\n")), 405);
  EXPECT_EQ(status_of(raw("GET / HTTP/1.1\r\nContent-Length: 5\r\n\r\nhello")), 413);
  EXPECT_EQ(status_of(raw("GET /" + std::string(10000, 'a') + " HTTP/1.1\r\n\r\n")), 431);
  const char hello[] = "\x16\x03\x01\x02\x00\x01\x00\x01\xfc\x03\x03\r\n\r\n";  // TLS to a plain port
  EXPECT_EQ(status_of(raw(std::string(hello, sizeof hello - 1))), 400);
  EXPECT_EQ(server_->bad_requests(), 4u);
  // The server still answers.
  EXPECT_EQ(status_of(get(port(), "/")), 200);
}

TEST_F(MapSiteTest, AHeadNotFinishedWithinTheReadTimeoutIs408AndFreesItsPlace) {
  start({}, 1, 0.3);
  RawHttp slow(port());
  slow.send("GET / HTTP/1.1\r\nHost: x\r\n");  // and never the blank line
  const std::string answer = slow.read_all();
  EXPECT_EQ(status_of(answer), 408);
  EXPECT_NE(body_of(answer).find("read timeout"), std::string::npos);
  ASSERT_TRUE(wait_until([&] { return server_->active_connections() == 0; }, 10s));
  EXPECT_EQ(status_of(get(port(), "/")), 200);
}

// The read timeout bounds the whole head, not each read: a client that
// sends a byte every 0.1 s (within the 0.5 s timeout each time) is still
// answered 408 once 0.5 s have passed since it connected.
TEST_F(MapSiteTest, AClientDribblingItsHeadIsCutOffAtTheTimeoutForTheWholeHead) {
  start({}, 4, 0.5);
  RawHttp slow(port());
  ASSERT_TRUE(wait_until([&] { return server_->active_connections() == 1; }, 5s));
  const auto started = std::chrono::steady_clock::now();
  const std::string head = "GET / HTTP/1.1\r\nHost: x\r\nX-Slow: ";
  bool cut_off = false;
  for (int i = 0; i < 50 && !cut_off; ++i) {  // 5 s of dribbling at most
    cut_off = !slow.send(std::string(1, head[static_cast<std::size_t>(i) % head.size()]));
    std::this_thread::sleep_for(100ms);
    if (server_->active_connections() == 0) cut_off = true;
  }
  EXPECT_TRUE(cut_off) << "a dribbling client kept its connection past the head's timeout";
  EXPECT_LT(std::chrono::steady_clock::now() - started, 3s);
}

TEST_F(MapSiteTest, UnknownVehiclesAndBadTimeRangesAreNamed) {
  fleet_.add_positions({at(1, 1000, 0, 0), at(3, 1000, 5, 5)});
  start();
  std::string r = get(port(), "/api/history?src=7");
  EXPECT_EQ(status_of(r), 404);
  EXPECT_NE(body_of(r).find("no vehicle 7 (vehicles with positions: 1, 3)"), std::string::npos) << r;
  r = get(port(), "/api/history?src=one");
  EXPECT_EQ(status_of(r), 400);
  EXPECT_NE(body_of(r).find("src: not a modem id"), std::string::npos);
  r = get(port(), "/api/history?from=yesterday");
  EXPECT_EQ(status_of(r), 400);
  EXPECT_NE(body_of(r).find("from: time \"yesterday\""), std::string::npos) << r;
  r = get(port(), "/kml/history.kml?from=2000&to=1000");
  EXPECT_EQ(status_of(r), 400);
  EXPECT_NE(body_of(r).find("from (2000) is after to (1000)"), std::string::npos) << r;
  r = get(port(), "/events?after=garbage");
  EXPECT_EQ(status_of(r), 400);
  EXPECT_EQ(status_of(get(port(), "/api/nothing")), 404);
}

TEST_F(MapSiteTest, HistoryHoldsThePositionsInTheRange) {
  fleet_.add_positions({at(1, 1000, 0, 0), at(1, 1001, 1, 0), at(1, 1002, 2, 0), at(2, 1001, 9, 9)});
  start();
  const std::string r = body_of(get(port(), "/api/history?from=1001&to=1002"));
  EXPECT_EQ(r.rfind("{\"from\":1001,\"to\":1002,\"vehicles\":[{\"src\":1,\"track\":[[1001,1,0,12.5,", 0), 0u) << r;
  EXPECT_EQ(r.find("[1000,"), std::string::npos);
  EXPECT_NE(r.find("{\"src\":2,\"track\":[[1001,9,9,12.5,"), std::string::npos) << r;
}

TEST_F(MapSiteTest, KmlNeedsLatLonAndHoldsEveryPositionWithItsTime) {
  fleet_.add_positions({at(1, 1000, 0, 0), at(1, 1001, 1, 0), at(2, 1000, 5, 5)});
  start();
  const std::string history = get(port(), "/kml/history.kml");
  EXPECT_EQ(status_of(history), 200);
  EXPECT_NE(history.find("Content-Type: application/vnd.google-earth.kml+xml"), std::string::npos);
  EXPECT_NE(history.find("<when>1970-01-01T00:16:40Z</when>"), std::string::npos);
  EXPECT_NE(history.find("<when>1970-01-01T00:16:41Z</when>"), std::string::npos);
  std::size_t points = 0;
  for (std::size_t at = history.find("<TimeStamp>"); at != std::string::npos; at = history.find("<TimeStamp>", at + 1)) ++points;
  EXPECT_EQ(points, 3u);
  const std::string link = body_of(get(port(), "/kml/network.kml"));
  EXPECT_NE(link.find("<href>http://127.0.0.1:" + std::to_string(port()) + "/kml/live.kml</href>"), std::string::npos) << link;
  EXPECT_NE(link.find("<refreshMode>onInterval</refreshMode>"), std::string::npos);
  const std::string live = body_of(get(port(), "/kml/live.kml"));
  EXPECT_NE(live.find("<name>node 2</name>"), std::string::npos);
  fleet_.add_positions({at(5, 1000, 0, 0, false)});
  const std::string refused = get(port(), "/kml/live.kml");
  EXPECT_EQ(status_of(refused), 409);
  EXPECT_NE(body_of(refused).find("telemetry.datum"), std::string::npos);
}

TEST_F(MapSiteTest, TheTokenGuardsDataButNotTheBuiltInFiles) {
  SiteOptions options;
  options.token = "0123456789abcdefXYZ";
  start(options);
  EXPECT_EQ(status_of(get(port(), "/")), 200);
  EXPECT_EQ(status_of(get(port(), "/leaflet.js")), 200);
  const std::string refused = get(port(), "/api/fleet");
  EXPECT_EQ(status_of(refused), 401);
  EXPECT_NE(body_of(refused).find("token"), std::string::npos);
  EXPECT_EQ(status_of(get(port(), "/api/fleet?token=0123456789abcdefXYz")), 401);
  EXPECT_EQ(status_of(get(port(), "/api/fleet?token=0123456789abcdef")), 401);
  EXPECT_EQ(status_of(get(port(), "/api/fleet?token=0123456789abcdefXYZ")), 200);
  EXPECT_EQ(status_of(get(port(), "/events?after=1:0", "Authorization: Bearer wrong\r\n")), 401);
  EXPECT_EQ(status_of(get(port(), "/kml/history.kml", "Authorization: Bearer 0123456789abcdefXYZ\r\n")), 200);
  const std::string link = body_of(get(port(), "/kml/network.kml?token=0123456789abcdefXYZ"));
  EXPECT_NE(link.find("/kml/live.kml?token=0123456789abcdefXYZ</href>"), std::string::npos) << link;
}

TEST_F(MapSiteTest, ConnectionsBeyondTheBoundAreAnswered503) {
  start({}, 2);
  RawHttp a(port()), b(port());  // two idle connections hold both places
  ASSERT_TRUE(a.connected() && b.connected());
  ASSERT_TRUE(wait_until([&] { return server_->active_connections() == 2; }, 10s));
  const std::string third = get(port(), "/");
  EXPECT_EQ(status_of(third), 503);
  EXPECT_NE(body_of(third).find("--max-connections"), std::string::npos);
  a.close();
  b.close();
  ASSERT_TRUE(wait_until([&] { return server_->active_connections() == 0; }, 10s));
  EXPECT_EQ(status_of(get(port(), "/")), 200);
}

// An MBTiles file with one tile at z 1, x 0, y 0 (counted from the north:
// row 1 from the south), format png.
std::string write_mbtiles(const std::string& path) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  const char* sql =
      "CREATE TABLE metadata (name TEXT, value TEXT); INSERT INTO metadata VALUES ('format', 'png');"
      "CREATE TABLE tiles (zoom_level INTEGER, tile_column INTEGER, tile_row INTEGER, tile_data BLOB);"
      "INSERT INTO tiles VALUES (1, 0, 1, X'89504E470D0A1A0A0001');";
  EXPECT_EQ(sqlite3_exec(db, sql, nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  return std::string("\x89PNG\r\n\x1a\n\x00\x01", 10);
}

TEST_F(MapSiteTest, TilesComeFromTheMbtilesFileWithItsRowsCountedFromTheSouth) {
  const std::string path = "/tmp/acomms-geov-tiles-" + std::to_string(::getpid()) + ".mbtiles";
  std::remove(path.c_str());
  const std::string png = write_mbtiles(path);
  SiteOptions options;
  options.mbtiles = std::make_shared<MbTiles>(path);
  start(options);
  EXPECT_EQ(body_of(get(port(), "/api/config")), "{\"tiles\":\"/tiles/{z}/{x}/{y}\",\"attribution\":\"\"}");
  const std::string tile = get(port(), "/tiles/1/0/0");
  EXPECT_EQ(status_of(tile), 200);
  EXPECT_NE(tile.find("Content-Type: image/png"), std::string::npos);
  EXPECT_EQ(body_of(tile), png);
  EXPECT_EQ(status_of(get(port(), "/tiles/1/0/1")), 404);  // the same row counted from the south is empty
  EXPECT_EQ(status_of(get(port(), "/tiles/1/5/0")), 404);  // outside the zoom's grid
  EXPECT_EQ(status_of(get(port(), "/tiles/1/0/0.png")), 400);
  EXPECT_EQ(status_of(get(port(), "/tiles/99/0/0")), 400);
  EXPECT_EQ(status_of(get(port(), "/tiles/../../etc/passwd")), 400);
  std::remove(path.c_str());
  EXPECT_THROW(MbTiles("/nonexistent/chart.mbtiles"), std::runtime_error);
}

TEST_F(MapSiteTest, WithoutTilesTheConfigAsksForTheMetricGrid) {
  start();
  EXPECT_EQ(body_of(get(port(), "/api/config")), "{\"tiles\":null,\"attribution\":\"\"}");
  EXPECT_EQ(status_of(get(port(), "/tiles/1/0/0")), 404);
}

// Updates since `after` on a stream that stays open.
std::string stream_until(RawHttp& http, const std::string& want) {
  return http.read_until([&](const std::string& text) { return text.find(want) != std::string::npos; });
}

TEST_F(MapSiteTest, EventsArriveLiveAndAResumedStreamMissesNone) {
  fleet_.add_positions({at(1, 1000, 0, 0)});
  start();
  const std::string epoch = std::to_string(fleet_.epoch());
  RawHttp live(port());
  live.send("GET /events?after=" + epoch + ":1 HTTP/1.1\r\n\r\n");
  stream_until(live, "retry: 2000");
  fleet_.add_positions({at(1, 1001, 1, 0)});
  std::string text = stream_until(live, "id: " + epoch + ":2\n");
  EXPECT_NE(text.find("Content-Type: text/event-stream"), std::string::npos);
  EXPECT_NE(text.find("\"added\":[[1001,1,0,12.5,"), std::string::npos) << text;
  live.close();
  // Two more while the viewer is away; it resumes with Last-Event-ID.
  fleet_.add_positions({at(1, 1002, 2, 0)});
  fleet_.add_positions({at(1, 1003, 3, 0)});
  RawHttp resumed(port());
  resumed.send("GET /events?after=" + epoch + ":1 HTTP/1.1\r\nLast-Event-ID: " + epoch + ":2\r\n\r\n");
  text = stream_until(resumed, "id: " + epoch + ":4\n");
  EXPECT_EQ(text.find("id: " + epoch + ":2\n"), std::string::npos);
  EXPECT_NE(text.find("id: " + epoch + ":3\n"), std::string::npos);
  EXPECT_NE(text.find("[[1002,2,0,"), std::string::npos);
  EXPECT_NE(text.find("[[1003,3,0,"), std::string::npos);
  // A page of an earlier server is told to reload.
  RawHttp stale(port());
  stale.send("GET /events?after=12:3 HTTP/1.1\r\n\r\n");
  EXPECT_NE(stream_until(stale, "event: reset").find("event: reset\ndata: {}"), std::string::npos);
}

TEST_F(MapSiteTest, ManyViewersEachGetEveryUpdateAndOneThatLeavesIsDropped) {
  constexpr int kViewers = 200;
  fleet_.add_positions({at(1, 1000, 0, 0)});
  start({}, kViewers + 8);
  const std::string epoch = std::to_string(fleet_.epoch());
  std::vector<std::unique_ptr<RawHttp>> viewers;
  for (int i = 0; i < kViewers; ++i) {
    viewers.push_back(std::make_unique<RawHttp>(port()));
    viewers.back()->send("GET /events?after=" + epoch + ":1 HTTP/1.1\r\n\r\n");
  }
  ASSERT_TRUE(wait_until([&] { return site_->open_streams() == kViewers; }, 20s)) << site_->open_streams();
  fleet_.add_positions({at(1, 1001, 1, 0)});
  int got = 0;
  for (auto& viewer : viewers) got += stream_until(*viewer, "[[1001,1,0,").find("[[1001,1,0,") != std::string::npos;
  EXPECT_EQ(got, kViewers);
  RecordProperty("viewers", got);
  // Viewers that go away cost nothing once the next keep-alive finds them gone.
  for (auto& viewer : viewers) viewer->close();
  EXPECT_TRUE(wait_until([&] { return site_->open_streams() == 0 && server_->active_connections() == 0; }, 10s))
      << site_->open_streams();
}

}  // namespace
}  // namespace acomms::cli::geov
