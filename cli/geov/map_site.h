#pragma once
// What `acommsctl geov serve` answers over HTTP: the page and Leaflet (built
// in), the fleet as JSON, its changes as server-sent events, its history
// for playback, KML for Google Earth, and tiles from an MBTiles file.
//
//   GET /, /geov_map.js, /geov_section.js, /geov_playback.js, /geov.js, /geov.css, /leaflet.js, /leaflet.css, /images/*.png
//   GET /api/config                     tiles or the metric grid
//   GET /api/fleet                      snapshot: every vehicle with its track
//   GET /api/history?from=T&to=T[&src=N]  positions in [from, to]
//   GET /api/section?src=N              PNG: transmission loss from the buoy
//                                       towards vehicle N (tl_section.h)
//   GET /events[?after=EPOCH:ID]        server-sent events (Last-Event-ID too)
//   GET /kml/network.kml                NetworkLink refreshing /kml/live.kml
//   GET /kml/live.kml                   last positions and tracks
//   GET /kml/history.kml?from=T&to=T[&src=N]  time-stamped positions
//   GET /tiles/Z/X/Y                    from --mbtiles
// T is seconds since the Unix epoch, "now", or -30s, -10m, -2h, -1d.
// A period (history, KML, playback) is cut to the positions held: without
// from and to it is all of them; a chosen one must overlap them (400
// naming both spans otherwise), and what it holds may last max_period_s at
// most (400 naming the bound), so one request cannot make the server
// format every position of a long mission at once.
//
// Everything but the built-in files needs the token when one is set
// (?token=T, or "Authorization: Bearer T"): the files hold no data, and a
// browser loads them before the page's script can add the token.
// Errors are an HTTP status and one line of text: 400 for a bad parameter
// (named), 401 without the token, 404 for an unknown path or vehicle
// (naming the known ones), 409 for KML of positions without lat/lon; the
// section's refusals are tl_section.h's (503 without an environment).
//
// Thread-safety: handle() is called concurrently from connection threads;
// the site holds no mutable state of its own besides atomics.

#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include "fleet.h"
#include "http_server.h"
#include "tile_source.h"
#include "tl_section.h"

namespace acomms::cli::geov {

struct SiteOptions {
  std::string token;        // empty: none needed
  std::string tile_url;     // a tile URL template for the page, or empty
  std::string attribution;  // shown under the tiles
  std::shared_ptr<MbTiles> mbtiles;
  double kml_refresh_s = 5;
  double heartbeat_s = 15;  // an idle event stream's keep-alive (and dead-viewer check)
  double max_period_s = 86400;  // the longest period of positions one request gets
  // The environment picture towards a vehicle at its last position (throws
  // SectionRefusal); empty: 503, no daemon's model to ask.
  std::function<SectionPicture(const telemetry::Position&)> section;
};

class MapSite {
 public:
  MapSite(Fleet& fleet, SiteOptions options);
  void handle(const HttpRequest& request, HttpResponder& responder);
  int open_streams() const { return open_streams_.load(); }

 private:
  bool authorized(const HttpRequest& request) const;
  void events(const HttpRequest& request, HttpResponder& responder);
  void history(const HttpRequest& request, HttpResponder& responder, bool kml);
  void live_kml(HttpResponder& responder);
  void network_link(const HttpRequest& request, HttpResponder& responder);
  void section(const HttpRequest& request, HttpResponder& responder);
  void tile(const std::string& path, HttpResponder& responder);

  Fleet& fleet_;
  SiteOptions options_;
  std::atomic<int> open_streams_{0};
};

}  // namespace acomms::cli::geov
