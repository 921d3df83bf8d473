// The browser test's requests and checks (geov_page_checks.h).
#include "geov_page_checks.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <map>

#include <google/protobuf/util/json_util.h>

#include "wait_until.h"

namespace acomms::testing::geov_page {

using namespace std::chrono_literals;

// "2026-11-27T04:20:22": what the page's datetime-local fields hold (UTC).
std::string utc_field(double t) {
  const std::time_t s = static_cast<std::time_t>(std::floor(t));
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", std::gmtime(&s));
  return text;
}

std::string http_get(int port, const std::string& target, int* status) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  timeval tv{10, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  std::string response;
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0) {
    const std::string request = "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\n\r\n";
    ::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
    char chunk[65536];
    ssize_t n;
    while ((n = ::recv(fd, chunk, sizeof chunk, 0)) > 0) response.append(chunk, static_cast<std::size_t>(n));
  }
  ::close(fd);
  if (status) *status = response.size() > 12 ? std::stoi(response.substr(9, 3)) : 0;
  const std::size_t head = response.find("\r\n\r\n");
  return head == std::string::npos ? "" : response.substr(head + 4);
}

Value parse_json(const std::string& text) {
  Value value;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(text, &value).ok()) << text.substr(0, 300);
  return value;
}

const Value& field(const Value& v, const std::string& key) { return v.struct_value().fields().at(key); }

// Progress on stdout, so that a slow CI run shows where its time went.
void step(const std::string& what) {
  static const auto start = std::chrono::steady_clock::now();
  std::printf("[geov %5.1f s] %s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
              what.c_str());
  std::fflush(stdout);
}

Value summary(WebDriver& browser) {
  return parse_json(browser.execute("return JSON.stringify(geov.summary());").string_value());
}

const Value* vehicle(const Value& s, int src) {
  for (const Value& v : field(s, "vehicles").list_value().values()) {
    if (field(v, "src").number_value() == src) return &v;
  }
  return nullptr;
}

void check_section(WebDriver& browser, int port, int src, double depth_m, double buoy_depth_m, double water_depth_m) {
  int status = 0;
  http_get(port, "/api/section?src=9", &status);
  EXPECT_EQ(status, 404);
  browser.execute("document.querySelector('#vehicles tbody tr[data-src=\"" + std::to_string(src) +
                  "\"]').click(); return true;");
  ASSERT_TRUE(wait_until([&] { return field(field(summary(browser), "section"), "loads").number_value() >= 1; }, 20s, 200ms))
      << browser.execute("return JSON.stringify(geov.summary().section);").string_value();
  const Value picture = parse_json(browser.execute(R"(
      const img = document.getElementById('section-img');
      const range = geov.summary().section.range_m;
      const length = Math.max(200, Math.ceil(range * 1.25 / 10) * 10);
      const c = document.createElement('canvas');
      c.width = img.naturalWidth; c.height = img.naturalHeight;
      const g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      const at = (x, y) => Array.from(g.getImageData(x, y, 1, 1).data.slice(0, 3));
      const x = Math.round(80 + 680 * range / length), y = Math.round(40 + 420 * )" +
                                                   std::to_string(depth_m) + " / " + std::to_string(water_depth_m) + R"();
      return JSON.stringify({ w: img.naturalWidth, h: img.naturalHeight, shown: !img.hidden && img.width > 0,
                              range: range, mark: at(x, y), ring: at(x + 6, y + 6),
                              buoy: at(80, Math.round(40 + 420 * )" + std::to_string(buoy_depth_m) + " / " +
                                                   std::to_string(water_depth_m) + R"()),
                              status: geov.summary().section.status });)").string_value());
  EXPECT_EQ(field(picture, "status").number_value(), 200);
  EXPECT_EQ(field(picture, "w").number_value(), 1100);
  EXPECT_EQ(field(picture, "h").number_value(), 520);
  EXPECT_TRUE(field(picture, "shown").bool_value());
  const double range = field(picture, "range").number_value();
  EXPECT_GT(range, 20);
  EXPECT_LT(range, 400);  // the test's vehicles stay within 260 m of the datum
  for (const char* mark : {"mark", "buoy"}) {
    for (const Value& channel : field(picture, mark).list_value().values()) EXPECT_EQ(channel.number_value(), 0) << mark;
  }
  for (const Value& channel : field(picture, "ring").list_value().values()) EXPECT_EQ(channel.number_value(), 255);

}

void check_chosen_period_playback(WebDriver& browser, int port, double t0) {
  auto set_period = [&](double from, double to, int speed) {
    browser.execute("document.getElementById('pb-from').value = '" + utc_field(from) +
                    "'; document.getElementById('pb-to').value = '" + utc_field(to) +
                    "'; document.getElementById('pb-speed').value = '" + std::to_string(speed) + "'; return true;");
  };
  set_period(t0 + 13, t0 + 3, 5);
  browser.execute("document.getElementById('pb-play').click(); return true;");
  EXPECT_TRUE(wait_until([&] { return field(summary(browser), "error").string_value().find("is after to") != std::string::npos; }, 5s, 100ms))
      << field(summary(browser), "error").string_value();
  set_period(t0 - 86400 * 400, t0 - 86400 * 399, 5);
  browser.execute("document.getElementById('pb-play').click(); return true;");
  EXPECT_TRUE(wait_until([&] { return field(summary(browser), "error").string_value().find("holds no positions") != std::string::npos; }, 5s, 100ms))
      << field(summary(browser), "error").string_value();
  EXPECT_EQ(field(summary(browser), "mode").string_value(), "live");

  const double from = std::floor(t0) + 3, to = std::floor(t0) + 13;
  set_period(from, to, 5);
  browser.execute("document.getElementById('pb-play').click(); return true;");
  ASSERT_TRUE(wait_until([&] { return field(summary(browser), "mode").string_value() == "playback"; }, 5s));
  EXPECT_EQ(field(summary(browser), "error").string_value(), "");
  // Under way: the clock inside the period, the slider between its ends.
  ASSERT_TRUE(wait_until(
      [&] {
        const Value pb = field(summary(browser), "playback");
        const double t = field(pb, "t").number_value();
        const double slider = std::stod(browser.execute("return document.getElementById('pb-slider').value;").string_value());
        return field(pb, "playing").bool_value() && t > field(pb, "from").number_value() + 1 &&
               t < field(pb, "to").number_value() - 1 && slider > 0 && slider < 1000;
      },
      5s, 50ms))
      << browser.execute("return JSON.stringify(geov.summary());").string_value();
  ASSERT_TRUE(wait_until(
      [&] {
        const Value pb = field(summary(browser), "playback");
        return !field(pb, "playing").bool_value() && field(pb, "t").number_value() >= field(pb, "to").number_value();
      },
      10s, 200ms))
      << browser.execute("return JSON.stringify(geov.summary());").string_value();
  const Value period = parse_json(http_get(port, "/api/history?from=" + std::to_string(from) + "&to=" + std::to_string(to)));
  const Value played = summary(browser);
  EXPECT_GE(field(field(played, "playback"), "from").number_value(), from);
  EXPECT_LE(field(field(played, "playback"), "to").number_value(), to);
  EXPECT_EQ(browser.execute("return document.getElementById('pb-slider').value;").string_value(), "1000");
  std::map<int, std::vector<double>> times;  // of the period's positions, by vehicle
  for (const Value& v : field(period, "vehicles").list_value().values()) {
    for (const Value& p : field(v, "track").list_value().values()) {
      times[static_cast<int>(field(v, "src").number_value())].push_back(p.list_value().values(0).number_value());
    }
  }
  for (int src : {1, 2}) {
    ASSERT_GE(times[src].size(), 5u) << src;
    EXPECT_EQ(field(*vehicle(played, src), "drawn").number_value(), times[src].size()) << src;
  }
  // The slider to the middle: the positions up to the middle of the period.
  browser.execute("const s = document.getElementById('pb-slider'); s.value = '500'; "
                  "s.dispatchEvent(new Event('input')); return true;");
  const Value middle = summary(browser);
  const double t_mid = field(field(middle, "playback"), "t").number_value();
  EXPECT_NEAR(t_mid, (field(field(middle, "playback"), "from").number_value() + field(field(middle, "playback"), "to").number_value()) / 2, 0.01);
  for (int src : {1, 2}) {
    const auto upto = std::count_if(times[src].begin(), times[src].end(), [&](double t) { return t <= t_mid; });
    EXPECT_EQ(field(*vehicle(middle, src), "drawn").number_value(), upto) << src;
    EXPECT_LT(upto, static_cast<long>(times[src].size())) << src;
  }
}

}  // namespace acomms::testing::geov_page
