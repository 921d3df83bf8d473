#pragma once
// What the browser test of the operator's map (geov_browser_test.cpp) asks
// the map server and its page: plain HTTP GETs, the page's own account of
// itself (geov.js: window.geov.summary()), and two whole features checked
// through the page as an operator uses them:
//   check_section: a vehicle's row clicked, the transmission-loss section
//     towards it shown, read back pixel by pixel: 1100 x 520, the vehicle's
//     mark black (ringed white) at the range the server names and its
//     depth, the buoy's black at range 0 and its depth; an unknown vehicle
//     is 404.
//   check_chosen_period_playback: [t0 + 3 s, t0 + 13 s] at 5x, typed into
//     the page's from/to fields: the clock and the slider run through it,
//     at its end every position of the period is drawn and no other, the
//     slider moved to the middle draws those up to the middle; an end
//     before the start and a period outside the positions held are refused
//     with the server's reason shown on the page.
//
// Thread-safety: the test's thread only (one WebDriver).

#include <google/protobuf/struct.pb.h>

#include <string>

#include "webdriver.h"

namespace acomms::testing::geov_page {

using google::protobuf::Value;

std::string http_get(int port, const std::string& target, int* status = nullptr);
Value parse_json(const std::string& text);
const Value& field(const Value& v, const std::string& key);
// Progress on stdout, so that a slow CI run shows where its time went.
void step(const std::string& what);
Value summary(WebDriver& browser);
const Value* vehicle(const Value& summary, int src);
std::string utc_field(double t);

void check_section(WebDriver& browser, int port, int src, double depth_m, double buoy_depth_m, double water_depth_m);
void check_chosen_period_playback(WebDriver& browser, int port, double t0);

}  // namespace acomms::testing::geov_page
