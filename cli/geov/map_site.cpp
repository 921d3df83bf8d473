#include "map_site.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

#include "assets.h"
#include "json_text.h"
#include "kml.h"
#include "rpc_error.h"
#include "time_arg.h"
#include "util/seconds.h"

namespace acomms::cli::geov {
namespace {

constexpr const char* kText = "text/plain; charset=utf-8";
constexpr const char* kJson = "application/json";
constexpr const char* kKml = "application/vnd.google-earth.kml+xml";

// A refusal the handler turns into its status and text.
struct HttpError {
  int status;
  std::string text;
};

// Token comparison in time independent of where the strings differ.
bool same_secret(const std::string& a, const std::string& b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i % (b.empty() ? 1 : b.size())]);
  return diff == 0 && !b.empty();
}

std::optional<std::string> param(const HttpRequest& request, const std::string& name) {
  auto it = request.query.find(name);
  if (it == request.query.end()) return std::nullopt;
  return it->second;
}

double time_param(const HttpRequest& request, const std::string& name, double fallback, double now) {
  auto text = param(request, name);
  if (!text) return fallback;
  try {
    return parse_time(*text, now);
  } catch (const UsageError& e) {
    throw HttpError{400, name + ": " + e.what()};
  }
}

std::string known_list(const std::set<int32_t>& vehicles) {
  if (vehicles.empty()) return "none yet";
  std::string out;
  for (int32_t src : vehicles) out += (out.empty() ? "" : ", ") + std::to_string(src);
  return out;
}

std::optional<int32_t> src_param(const HttpRequest& request, const Fleet& fleet) {
  auto text = param(request, "src");
  if (!text) return std::nullopt;
  int32_t src = 0;
  auto [end, error] = std::from_chars(text->data(), text->data() + text->size(), src);
  if (error != std::errc() || end != text->data() + text->size()) {
    throw HttpError{400, "src: not a modem id: \"" + text->substr(0, 32) + "\""};
  }
  if (!fleet.vehicles().count(src)) {
    throw HttpError{404, "no vehicle " + std::to_string(src) + " (vehicles with positions: " + known_list(fleet.vehicles()) + ")"};
  }
  return src;
}

bool valid_host(const std::string& host) {
  if (host.empty() || host.size() > 255) return false;
  for (char c : host) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == ':' || c == '[' || c == ']')) {
      return false;
    }
  }
  return true;
}

}  // namespace

const EmbeddedFile* find_asset(std::string_view path) {
  for (const EmbeddedFile& file : embedded_assets()) {
    if (file.name == path) return &file;
  }
  return nullptr;
}

MapSite::MapSite(Fleet& fleet, SiteOptions options) : fleet_(fleet), options_(std::move(options)) {}

bool MapSite::authorized(const HttpRequest& request) const {
  if (options_.token.empty()) return true;
  if (auto token = param(request, "token"); token && same_secret(*token, options_.token)) return true;
  auto header = request.headers.find("authorization");
  return header != request.headers.end() && header->second.rfind("Bearer ", 0) == 0 &&
         same_secret(header->second.substr(7), options_.token);
}

void MapSite::handle(const HttpRequest& request, HttpResponder& responder) {
  const std::string& path = request.path;
  if (const EmbeddedFile* file = find_asset(path)) {
    const bool text = file->type.rfind("text/", 0) == 0;
    return responder.send(200, std::string(file->type) + (text ? "; charset=utf-8" : ""), file->bytes);
  }
  if (!authorized(request)) {
    return responder.send(401, kText, "this map needs its token: open it as /?token=... (see --token-file)\n",
                          "WWW-Authenticate: Bearer realm=\"acomms map\"\r\n");
  }
  try {
    if (path == "/api/config") {
      std::string tiles = options_.mbtiles ? "/tiles/{z}/{x}/{y}" : options_.tile_url;
      return responder.send(200, kJson, "{\"tiles\":" + (tiles.empty() ? "null" : json_string(tiles)) +
                                            ",\"attribution\":" + json_string(options_.attribution) + "}");
    }
    if (path == "/api/fleet") return responder.send(200, kJson, fleet_.snapshot_json(util::unix_seconds_now()));
    if (path == "/api/history") return history(request, responder, false);
    if (path == "/api/section") return section(request, responder);
    if (path == "/events") return events(request, responder);
    if (path == "/kml/network.kml") return network_link(request, responder);
    if (path == "/kml/live.kml") return live_kml(responder);
    if (path == "/kml/history.kml") return history(request, responder, true);
    if (path.rfind("/tiles/", 0) == 0 && options_.mbtiles) return tile(path, responder);
    responder.send(404, kText, "no such page: " + path.substr(0, 200) + "\n");
  } catch (const HttpError& e) {
    responder.send(e.status, kText, e.text + "\n");
  }
}

void MapSite::history(const HttpRequest& request, HttpResponder& responder, bool kml) {
  const double now = util::unix_seconds_now();
  const bool chosen = param(request, "from") || param(request, "to");
  double from = time_param(request, "from", -std::numeric_limits<double>::infinity(), now);
  double to = time_param(request, "to", now, now);
  if (from > to) {
    throw HttpError{400, "from (" + json_number(from) + ") is after to (" + json_number(to) + ")"};
  }
  const std::optional<int32_t> src = src_param(request, fleet_);
  const auto held = fleet_.span(src);
  if (!held) {
    if (chosen) throw HttpError{400, "no positions held yet: the period has nothing to show"};
    from = to = now;
  } else {
    if (to < held->first || from > held->second) {
      const std::string start = std::isfinite(from) ? kml_time(from) : "the beginning";
      throw HttpError{400, "the period " + start + " to " + kml_time(to) +
                               " holds no positions: those held run from " + kml_time(held->first) + " to " +
                               kml_time(held->second)};
    }
    from = std::max(from, held->first);
    to = std::min(to, held->second);
    // No period chosen (a saved Google Earth link, "all of it"): the newest
    // --max-period of what is held, rather than a refusal once a day has passed.
    if (!chosen) from = std::max(from, to - options_.max_period_s);
    if (to - from > options_.max_period_s) {
      throw HttpError{400, "the period holds " + json_number(std::round((to - from) / 36) / 100) +
                               " h of positions; at most " + json_number(options_.max_period_s / 3600) +
                               " h at once (--max-period): choose a shorter one"};
    }
  }
  const VehicleTracks tracks = fleet_.history(from, to, src);
  if (kml) {
    if (!kml_placeable(tracks)) {
      throw HttpError{409, "the positions have no lat/lon (the daemons' config sets no telemetry.datum): KML needs them"};
    }
    std::ostringstream out;
    write_fleet_history_kml(tracks, "acomms fleet from " + kml_time(from) + " to " + kml_time(to), out);
    return responder.send(200, kKml, out.str(),
                          "Content-Disposition: attachment; filename=\"acomms-history.kml\"\r\n");
  }
  std::string out = "{\"from\":" + json_number(from) + ",\"to\":" + json_number(to) + ",\"vehicles\":[";
  bool first = true;
  for (const auto& [id, track] : tracks) {
    out += std::string(first ? "" : ",") + "{\"src\":" + std::to_string(id) + ",\"track\":[";
    first = false;
    for (std::size_t i = 0; i < track.size(); ++i) {
      if (i) out += ',';
      out += position_json(track[i]);
    }
    out += "]}";
  }
  responder.send(200, kJson, out + "]}");
}

void MapSite::section(const HttpRequest& request, HttpResponder& responder) {
  const std::optional<int32_t> src = src_param(request, fleet_);
  if (!src) throw HttpError{400, "src: give the vehicle's modem id, e.g. /api/section?src=2"};
  if (!options_.section) throw HttpError{503, "no environment: this server asks no daemon's model"};
  const std::optional<telemetry::Position> vehicle = fleet_.last_position(*src);
  if (!vehicle) throw HttpError{404, "no position of vehicle " + std::to_string(*src) + " yet"};
  try {
    const SectionPicture picture = options_.section(*vehicle);
    responder.send(200, "image/png", picture.png,
                   "X-Acomms-Range-M: " + json_number(std::round(picture.range_m * 10) / 10) + "\r\n");
  } catch (const SectionRefusal& refusal) {
    throw HttpError{refusal.status, refusal.text};
  }
}

void MapSite::live_kml(HttpResponder& responder) {
  const VehicleTracks tracks = fleet_.history(-std::numeric_limits<double>::infinity(),
                                              std::numeric_limits<double>::infinity());
  if (!kml_placeable(tracks)) {
    throw HttpError{409, "the positions have no lat/lon (the daemons' config sets no telemetry.datum): KML needs them"};
  }
  std::ostringstream out;
  write_fleet_live_kml(tracks, out);
  responder.send(200, kKml, out.str());
}

void MapSite::network_link(const HttpRequest& request, HttpResponder& responder) {
  auto host = request.headers.find("host");
  if (host == request.headers.end() || !valid_host(host->second)) {
    throw HttpError{400, "a NetworkLink needs the Host header (host:port) to point back here"};
  }
  std::string href = "http://" + host->second + "/kml/live.kml";
  if (!options_.token.empty()) href += "?token=" + options_.token;
  std::ostringstream out;
  write_network_link_kml(href, options_.kml_refresh_s, out);
  responder.send(200, kKml, out.str(), "Content-Disposition: attachment; filename=\"acomms-live.kml\"\r\n");
}

void MapSite::tile(const std::string& path, HttpResponder& responder) {
  long long z = -1, x = -1, y = -1;
  char extra = 0;
  if (std::sscanf(path.c_str(), "/tiles/%lld/%lld/%lld%c", &z, &x, &y, &extra) != 3 || z < 0 || z > 30) {
    throw HttpError{400, "a tile is /tiles/Z/X/Y with whole numbers, Z at most 30"};
  }
  auto bytes = options_.mbtiles->tile(static_cast<int>(z), x, y);
  if (!bytes) throw HttpError{404, "no tile " + path.substr(7) + " in the MBTiles file"};
  responder.send(200, options_.mbtiles->content_type(), *bytes);
}

void MapSite::events(const HttpRequest& request, HttpResponder& responder) {
  // Where to resume: EventSource's own Last-Event-ID after a dropped
  // connection is newer than the ?after the page opened the stream with.
  std::string after;
  if (auto header = request.headers.find("last-event-id"); header != request.headers.end()) {
    after = header->second;
  } else if (auto query = param(request, "after")) {
    after = *query;
  }
  uint64_t epoch = fleet_.epoch(), id = fleet_.last_update_id();
  if (!after.empty()) {
    unsigned long long e = 0, n = 0;
    char extra = 0;
    if (std::sscanf(after.c_str(), "%llu:%llu%c", &e, &n, &extra) != 2) {
      throw HttpError{400, "after: want EPOCH:ID as the last event's id, got \"" + after.substr(0, 40) + "\""};
    }
    epoch = e;
    id = n;
  }
  if (!responder.start_stream("text/event-stream")) return;
  ++open_streams_;
  struct Leave {
    std::atomic<int>& count;
    ~Leave() { --count; }
  } leave{open_streams_};
  if (!responder.write("retry: 2000\n\n")) return;
  const auto heartbeat = std::chrono::milliseconds(static_cast<int64_t>(options_.heartbeat_s * 1000));
  while (true) {
    FleetUpdates updates = fleet_.updates_after(epoch, id, heartbeat);
    if (updates.reset) {
      // The page reloads the snapshot and opens a new stream.
      responder.write("event: reset\ndata: {}\n\n");
      return;
    }
    if (updates.closed) return;
    if (updates.events.empty()) {
      if (!responder.write(": keep-alive\n\n")) return;  // a viewer that left ends here
      continue;
    }
    std::string batch;
    for (const auto& [n, json] : updates.events) {
      batch += "id: " + std::to_string(epoch) + ":" + std::to_string(n) + "\ndata: " + json + "\n\n";
      id = n;
    }
    if (!responder.write(batch)) return;
  }
}

}  // namespace acomms::cli::geov
