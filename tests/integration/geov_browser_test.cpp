// The operator's map in a real browser (issue 33): two vehicles (nodes 1
// and 2) fed navigation through the API and a topside (node 3) that
// receives their position telemetry, three real acommsd processes on the
// loopback sim channel; `acommsctl geov serve` follows the topside; Debian's
// chromium, headless and unable to resolve any host but the loopback's,
// opens the page through chromedriver (webdriver.h).
//
// It checks: both vehicles' markers and tracks are drawn and move as new
// positions arrive; the map server restarts and the page reconnects by
// itself; the topside daemon is SIGKILLed and restarted under the page, the
// map server resumes its stream (SubscribeRequest.after) and the page goes on
// live; the page ends holding every position the topside holds (no gap); every resource the page loaded came from the map
// server; a vehicle clicked shows the buoy's transmission-loss section
// towards it, the vehicle marked at its depth; playback of a chosen period
// (bad ones refused with the server's reason) runs through it on the
// slider to its end with every position of the period drawn, and the
// slider moved back shows the positions up to there; the NetworkLink and the history KML parse
// as KML 2.2 and hold every position the topside's Track holds. A
// screenshot is kept as geov_map.png beside this test's binary. The section
// and playback checks, and the small HTTP and JSON helpers, are in
// geov_page_checks.h.
//
// Real time, bounded: the telemetry travels in 2.5 s TDMA slots; the whole
// test takes about 40 s. Skipped, with one message, only when chromium or
// chromedriver is not installed (CI installs both).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <ctime>
#include <fstream>
#include <map>
#include <regex>
#include <thread>

#include <google/protobuf/util/json_util.h>

#include "daemon_harness.h"
#include "geov_page_checks.h"
#include "util/seconds.h"
#include "webdriver.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using google::protobuf::Value;
using namespace geov_page;

constexpr int kTopside = 3;
const std::vector<int> kNodes = {1, 2, kTopside};

std::string name(int id) { return id == kTopside ? "topside" : "vehicle" + std::to_string(id); }

// 60 m of water over sand, the buoy's modem at 5 m; beams fixed so that a
// section runs in a fraction of a second.
constexpr double kWaterDepthM = 60;
const char* const kBuoyEnvironment =
    "gram { base { title: \"test shelf\" frequency_hz: 10000 source_depth_m: 5 beam_count: 400\n"
    "  launch_angle_min_deg: -80 launch_angle_max_deg: 80 box_depth_m: 70 box_range_m: 1000\n"
    "  sound_speed { depth_m: 0 speed_mps: 1510 } sound_speed { depth_m: 20 speed_mps: 1505 }\n"
    "  sound_speed { depth_m: 60 speed_mps: 1500 }\n"
    "  bottom { kind: HALF_SPACE half_space { speed_mps: 1700 density_ratio: 1.9 attenuation_np_per_m: 0.001 } } } }\n";

// Where vehicle `id` is at `s` seconds into the test: circles of 60 m and
// 90 m around two points, so that both markers move every second.
std::pair<double, double> track_at(int id, double s) {
  const double r = id == 1 ? 60 : 90, cx = id == 1 ? -80 : 120, w = 2 * M_PI / 120;
  return {cx + r * std::cos(w * s + id), 40 + r * std::sin(w * s + id)};
}

class GeovBrowser : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    browser_ = WebDriver::find_browser(why);
    if (!browser_) GTEST_SKIP() << why;
    dir_ = fs::path("/tmp") / ("acomms-geov-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::map<int, int> port;
    for (int id : kNodes) port[id] = free_udp_port();
    for (int id : kNodes) {
      std::ofstream config(dir_ / (name(id) + ".conf"));
      config << DaemonConfig{.data_dir = dir_ / name(id), .unix_socket = socket(id)}.text()
             << "driver { name: \"sim\" modem_id: " << id << " sim { listen: \"127.0.0.1:" << port[id] << "\"";
      for (int other : kNodes) {
        if (other != id) config << " peers: \"127.0.0.1:" << port[other] << "\"";
      }
      config << " } }\nmac { name: \"fixed\"";
      for (int slot : kNodes) config << " slot { src: " << slot << " rate: 5 seconds: 2.5 }";
      config << " max_range_m: 400 }\n"
             << "telemetry { tau_s: 1 ttl_s: 600 datum { lat: 41.52 lon: -70.67 }"
             << (id == kTopside ? "" : " receiver: 3") << " }\n";
      // The buoy's environment, for the page's transmission-loss section.
      if (id == kTopside) config << kBuoyEnvironment;
    }
    for (int id : kNodes) {
      daemons_[id] = std::make_unique<ChildProcess>(
          ACOMMSD_BINARY, std::vector<std::string>{"--config", (dir_ / (name(id) + ".conf")).string()},
          (dir_ / name(id)).string());
    }
    for (int id : kNodes) ASSERT_TRUE(wait_serving(*daemons_[id], socket(id))) << daemons_[id]->stderr_text();
    t0_ = util::unix_seconds_now();
    last_fix_[1] = 0;  // both entries made before the feeders write them
    last_fix_[2] = 0;
    for (int id : {1, 2}) feeders_.emplace_back([this, id] { feed(id); });
  }

  void TearDown() override {
    stop_feeding();
    if (map_ && map_->running()) {
      map_->signal(SIGTERM);
      EXPECT_EQ(map_->wait(10s), std::optional<int>(0)) << map_->stderr_text();
    }
    for (auto& [id, daemon] : daemons_) {
      if (daemon->running()) {
        daemon->signal(SIGTERM);
        daemon->wait(15s);
      }
    }
    if (!HasFailure() && !dir_.empty()) fs::remove_all(dir_);
  }

  std::string socket(int id) const { return (dir_ / (name(id) + ".sock")).string(); }

  // Navigation as a vehicle's computer gives it: a fix every 0.25 s, now.
  void feed(int id) {
    grpc::ClientContext context;
    v1::SubmitNavigationResponse response;
    auto stub = api(socket(id));
    auto writer = stub->SubmitNavigation(&context, &response);
    while (!stop_.load()) {
      const double now = util::unix_seconds_now();
      const auto [x, y] = track_at(id, now - t0_);
      v1::NavigationFix fix;
      fix.set_time(now);
      fix.mutable_local()->set_x(x);
      fix.mutable_local()->set_y(y);
      fix.set_depth(10 + 5 * id);
      if (!writer->Write(fix)) break;
      last_fix_[id] = now;
      std::this_thread::sleep_for(250ms);
    }
    writer->WritesDone();
    writer->Finish();
  }
  void stop_feeding() {
    stop_ = true;
    for (auto& feeder : feeders_) {
      if (feeder.joinable()) feeder.join();
    }
  }

  v1::TrackResponse track(int src) {
    grpc::ClientContext context;
    v1::TrackRequest request;
    request.set_src(src);
    v1::TrackResponse response;
    api(socket(kTopside))->Track(&context, request, &response);
    return response;
  }

  std::string kml_json(const std::string& kml, const std::string& label) {
    const fs::path file = dir_ / (label + ".kml");
    std::ofstream(file) << kml;
    RunResult r = run("/usr/bin/python3", {ACOMMS_SOURCE_DIR "/tests/integration/kml_positions.py", file.string()},
                      (dir_ / ("parse-" + label)).string());
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    return r.out;
  }

  std::optional<std::pair<std::string, std::string>> browser_;
  fs::path dir_;
  std::map<int, std::unique_ptr<ChildProcess>> daemons_;
  std::unique_ptr<ChildProcess> map_;
  std::vector<std::thread> feeders_;
  std::atomic<bool> stop_{false};
  std::map<int, std::atomic<double>> last_fix_{};
  double t0_ = 0;
};

TEST_F(GeovBrowser, BothVehiclesMoveLivePlayBackAndExportAsKml) {
  const auto started = std::chrono::steady_clock::now();
  map_ = std::make_unique<ChildProcess>(
      ACOMMSCTL_BINARY,
      std::vector<std::string>{"--socket", socket(kTopside), "geov", "serve", "--listen", "127.0.0.1:0", "--poll", "0.5"},
      (dir_ / "geov").string());
  std::smatch match;
  const std::regex serving("serving http://127\\.0\\.0\\.1:([0-9]+)/");
  ASSERT_TRUE(wait_until([&] { const std::string err = map_->stderr_text(); return std::regex_search(err, match, serving); }, 10s))
      << map_->stderr_text();
  const std::string err = map_->stderr_text();
  std::regex_search(err, match, serving);
  const int port = std::stoi(match[1]);
  const std::string origin = "http://127.0.0.1:" + std::to_string(port) + "/";

  // The page's size: everything it loads.
  std::size_t page_bytes = 0;
  for (const char* asset : {"/", "/geov_map.js", "/geov_section.js", "/geov_playback.js", "/geov.js", "/geov.css", "/leaflet.js", "/leaflet.css"}) {
    int status = 0;
    page_bytes += http_get(port, asset, &status).size();
    EXPECT_EQ(status, 200) << asset;
  }
  RecordProperty("page_bytes", static_cast<int>(page_bytes));

  step("starting chromium");
  WebDriver browser(browser_->first, browser_->second, dir_);
  step("opening " + origin);
  browser.navigate(origin);
  const double load_ms = browser.execute(
      "const n = performance.getEntriesByType('navigation')[0]; return n.loadEventEnd - n.startTime;").number_value();
  RecordProperty("page_load_ms", static_cast<int>(load_ms));
  std::printf("page: %zu bytes, loaded in %.0f ms\n", page_bytes, load_ms);

  step("waiting for both vehicles");
  // 1. Both vehicles drawn: a marker and a track of two positions or more.
  Value first;
  ASSERT_TRUE(wait_until(
      [&] {
        first = summary(browser);
        for (int src : {1, 2}) {
          const Value* v = vehicle(first, src);
          if (!v || field(*v, "marker").has_null_value() || field(*v, "drawn").number_value() < 2) return false;
        }
        return true;
      },
      30s, 250ms))
      << browser.execute("return JSON.stringify(geov.summary());").string_value() << "\n" << map_->stderr_text();
  EXPECT_EQ(browser.execute("return document.querySelectorAll('.geov-marker').length;").number_value(), 2);
  // Both tracks drawn in the view (Leaflet leaves a path outside it empty).
  EXPECT_TRUE(wait_until(
      [&] {
        return browser.execute("return [...document.querySelectorAll('path.geov-track')].filter(p => (p.getAttribute('d') || '').length > 10).length;")
                   .number_value() == 2;
      },
      5s, 200ms));
  EXPECT_EQ(field(first, "mode").string_value(), "live");
  // The panel's table: a row per vehicle (redrawn every second).
  EXPECT_TRUE(wait_until(
      [&] { return browser.execute("return document.querySelectorAll('#vehicles tbody tr').length;").number_value() == 2; },
      3s, 200ms));

  step("waiting for both to move");
  // 2. They move as new positions arrive, pushed to the page (no reload).
  ASSERT_TRUE(wait_until(
      [&] {
        const Value now = summary(browser);
        for (int src : {1, 2}) {
          const Value& a = *vehicle(first, src);
          const Value* b = vehicle(now, src);
          if (field(*b, "positions").number_value() <= field(a, "positions").number_value()) return false;
          if (field(*b, "drawn").number_value() <= field(a, "drawn").number_value()) return false;
          const auto& ma = field(a, "marker").list_value().values();
          const auto& mb = field(*b, "marker").list_value().values();
          if (ma[0].number_value() == mb[0].number_value() && ma[1].number_value() == mb[1].number_value()) return false;
        }
        return field(now, "updates").number_value() > 0;
      },
      25s, 250ms))
      << browser.execute("return JSON.stringify(geov.summary());").string_value();

  // 2b. The map server restarts: the page reconnects by itself, is told
  // its ids are of the old server, reloads the snapshot and goes on live.
  step("restarting the map server");
  const Value before_restart = summary(browser);
  map_->signal(SIGTERM);
  ASSERT_EQ(map_->wait(10s), std::optional<int>(0)) << map_->stderr_text();
  map_ = std::make_unique<ChildProcess>(
      ACOMMSCTL_BINARY,
      std::vector<std::string>{"--socket", socket(kTopside), "geov", "serve", "--listen",
                               "127.0.0.1:" + std::to_string(port), "--poll", "0.5"},
      (dir_ / "geov-2").string());
  ASSERT_TRUE(wait_until(
      [&] {
        const Value now = summary(browser);
        if (field(now, "resets").number_value() < 1 || !field(now, "connected").bool_value()) return false;
        for (int src : {1, 2}) {
          if (field(*vehicle(now, src), "positions").number_value() <=
              field(*vehicle(before_restart, src), "positions").number_value()) {
            return false;
          }
        }
        return true;
      },
      25s, 250ms))
      << browser.execute("return JSON.stringify(geov.summary());").string_value() << "\n" << map_->stderr_text();

  // 2c. The topside daemon is killed (SIGKILL: no goodbye to the map
  // server) and started again on its store: the map server reconnects by
  // itself, resumes the daemon's stream after the last seq it handled, and
  // the page goes on live without a reload. That no position went missing
  // is checked at the end (7).
  step("killing and restarting the topside daemon");
  const Value before_kill = summary(browser);
  daemons_[kTopside]->signal(SIGKILL);
  daemons_[kTopside]->wait(10s);
  ASSERT_EQ(daemons_[kTopside]->exit_signal(), SIGKILL);
  std::this_thread::sleep_for(1500ms);  // the feed notices, and the vehicles send meanwhile
  daemons_[kTopside] = std::make_unique<ChildProcess>(
      ACOMMSD_BINARY, std::vector<std::string>{"--config", (dir_ / (name(kTopside) + ".conf")).string()},
      (dir_ / name(kTopside)).string());
  ASSERT_TRUE(wait_serving(*daemons_[kTopside], socket(kTopside))) << daemons_[kTopside]->stderr_text();
  ASSERT_TRUE(wait_until(
      [&] {
        const std::string said = map_->stderr_text();
        if (said.find("reconnecting") == std::string::npos || said.find("stream resumed after seq") == std::string::npos) return false;
        const Value now = summary(browser);
        if (!field(now, "connected").bool_value()) return false;
        for (int src : {1, 2}) {
          if (field(*vehicle(now, src), "positions").number_value() <=
              field(*vehicle(before_kill, src), "positions").number_value()) {
            return false;
          }
        }
        return true;
      },
      30s, 250ms))
      << browser.execute("return JSON.stringify(geov.summary());").string_value() << "\n" << map_->stderr_text();
  // The page kept its connection to the map server: no reset, no reload.
  EXPECT_EQ(field(summary(browser), "resets").number_value(), field(before_kill, "resets").number_value());

  // 3. Nothing came from anywhere but the map server.
  const Value resources = browser.execute("return performance.getEntriesByType('resource').map(e => e.name);");
  EXPECT_GE(resources.list_value().values_size(), 4);
  for (const Value& r : resources.list_value().values()) EXPECT_EQ(r.string_value().rfind(origin, 0), 0u) << r.string_value();

  step("environment");
  // 4. The environment: vehicle 2 clicked, the buoy's transmission-loss
  // section towards it is shown, the vehicle marked at its depth.
  check_section(browser, port, 2, 20, 5, kWaterDepthM);
  step("playback of a chosen period");
  // 5. A chosen period played back, bad ones refused (geov_page_checks.h).
  check_chosen_period_playback(browser, port, t0_);
  browser.execute("document.getElementById('pb-live').click(); return true;");
  EXPECT_EQ(field(summary(browser), "mode").string_value(), "live");
  const std::string png = browser.screenshot_png();
  ASSERT_EQ(png.substr(1, 3), "PNG");
  std::ofstream(fs::path(GEOV_OUTPUT_DIR) / "geov_map.png", std::ios::binary) << png;

  step("KML");
  // 6 and 7. KML: the vehicles stop; once the topside and the map hold the same
  // track, the NetworkLink's document and the history hold every position.
  stop_feeding();
  std::map<int, v1::TrackResponse> tracks;
  ASSERT_TRUE(wait_until(
      [&] {
        for (int src : {1, 2}) {
          tracks[src] = track(src);
          const int n = tracks[src].positions_size();
          if (n == 0 || tracks[src].positions(n - 1).time() < std::floor(last_fix_[src].load())) return false;
        }
        const Value history = parse_json(http_get(port, "/api/history"));
        for (const Value& v : field(history, "vehicles").list_value().values()) {
          const int src = static_cast<int>(field(v, "src").number_value());
          if (field(v, "track").list_value().values_size() != tracks[src].positions_size()) return false;
        }
        return true;
      },
      25s, 500ms));
  // The page holds every position, through the map server's restart and
  // the daemon's SIGKILL: no gap, none twice.
  EXPECT_TRUE(wait_until(
      [&] {
        const Value now = summary(browser);
        for (int src : {1, 2}) {
          if (field(*vehicle(now, src), "positions").number_value() != tracks[src].positions_size()) return false;
        }
        return true;
      },
      5s, 200ms))
      << browser.execute("return JSON.stringify(geov.summary());").string_value();
  const Value link = parse_json(kml_json(http_get(port, "/kml/network.kml"), "network"));
  ASSERT_EQ(field(link, "hrefs").list_value().values_size(), 1);
  const std::string href = field(link, "hrefs").list_value().values(0).string_value();
  ASSERT_EQ(href, origin + "kml/live.kml");
  const Value live = parse_json(kml_json(http_get(port, "/kml/live.kml"), "live"));
  const Value history = parse_json(kml_json(http_get(port, "/kml/history.kml"), "history"));
  for (int src : {1, 2}) {
    const v1::TrackResponse& t = tracks[src];
    const auto& line = field(field(live, "lines"), "node " + std::to_string(src) + " track").list_value();
    ASSERT_EQ(line.values_size(), t.positions_size()) << src;
    std::map<double, std::vector<double>> stamped;
    for (const Value& s : field(history, "stamped").list_value().values()) {
      if (s.list_value().values(0).string_value() != "node " + std::to_string(src)) continue;
      stamped[s.list_value().values(1).number_value()] = {s.list_value().values(2).number_value(),
                                                          s.list_value().values(3).number_value(),
                                                          s.list_value().values(4).number_value()};
    }
    ASSERT_EQ(stamped.size(), static_cast<std::size_t>(t.positions_size())) << src;
    // KML carries 10 significant digits (kml.h): 1e-8 degree, about 1 mm,
    // against positions on a 1 m grid.
    constexpr double kDegrees = 1e-8;
    for (int i = 0; i < t.positions_size(); ++i) {
      const telemetry::Position& p = t.positions(i);
      const auto& l = line.values(i).list_value();
      EXPECT_NEAR(l.values(0).number_value(), p.lon(), kDegrees);
      EXPECT_NEAR(l.values(1).number_value(), p.lat(), kDegrees);
      ASSERT_TRUE(stamped.count(p.time())) << src << " " << p.time();
      EXPECT_NEAR(stamped[p.time()][0], p.lon(), kDegrees);
      EXPECT_NEAR(stamped[p.time()][1], p.lat(), kDegrees);
      EXPECT_NEAR(stamped[p.time()][2], -p.depth(), 1e-9);
    }
    RecordProperty("positions_node" + std::to_string(src), t.positions_size());
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  RecordProperty("browser_test_seconds", static_cast<int>(seconds));
  EXPECT_LT(seconds, 70);
}

}  // namespace
}  // namespace acomms::testing
