#include "track_command.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "api_client.h"
#include "events_command.h"
#include "global_options.h"
#include "kml.h"
#include "output.h"
#include "rpc_error.h"
#include "time_arg.h"
#include "util/seconds.h"

namespace acomms::cli {
namespace {

struct TrackOptions {
  int32_t src = 0;
  std::string since;
  bool csv = false;
  std::string kml;
};

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

void run_track(const GlobalOptions& global, const TrackOptions& options) {
  v1::TrackRequest request;
  request.set_src(options.src);
  if (!options.since.empty()) {
    const double now = util::unix_seconds_now();
    request.set_since(parse_time(options.since, now));
  }
  ApiClient client(global);
  v1::TrackResponse response = client.call(&v1::Acomms::Stub::Track, request);
  if (response.truncated()) std::fprintf(stderr, "acommsctl: more positions than one answer holds: ask again with --since\n");
  if (!options.kml.empty()) {
    // Built first: a track without lat/lon leaves no half-written file.
    std::ostringstream kml;
    write_track_kml(response, options.src, kml);
    std::ofstream file(options.kml);
    if (!file) throw UsageError("track: cannot write " + options.kml);
    if (!(file << kml.str()).flush()) throw UsageError("track: writing " + options.kml + " failed");
    if (response.positions_size() == 0) {
      std::fprintf(stderr, "no positions from node %d%s: %s is a KML document with no track\n", options.src,
                   options.since.empty() ? "" : (" since " + options.since).c_str(), options.kml.c_str());
    } else {
      std::fprintf(stderr, "%d positions written to %s\n", response.positions_size(), options.kml.c_str());
    }
    return;
  }
  if (global.json) {
    print_json(response);
    return;
  }
  write_track_csv(response, std::cout);
}

}  // namespace

void write_track_csv(const v1::TrackResponse& track, std::ostream& out) {
  out << "time,x,y,z,lat,lon,depth,full\n";
  for (const telemetry::Position& p : track.positions()) {
    out << number(p.time()) << ',' << number(p.x()) << ',' << number(p.y()) << ',' << number(p.z()) << ','
        << (p.has_lat() ? number(p.lat()) : "") << ',' << (p.has_lon() ? number(p.lon()) : "") << ','
        << number(p.depth()) << ',' << (p.full() ? 1 : 0) << '\n';
  }
}

void write_track_kml(const v1::TrackResponse& track, int32_t src, std::ostream& out) {
  for (const telemetry::Position& p : track.positions()) {
    if (!p.has_lat()) {
      throw UsageError("track: the positions have no lat/lon (the daemon's config sets no telemetry.datum): use --csv");
    }
  }
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n<Document>\n"
      << "<name>acomms track of node " << src << "</name>\n";
  if (track.positions_size() == 0) {
    // Still a valid document (a periodic export keeps its viewer happy),
    // and it says why it shows nothing.
    out << "<description>no positions received from node " << src << "</description>\n</Document>\n</kml>\n";
    return;
  }
  // KML 2.2: a LineString needs two coordinates or more; one is a Point.
  const char* geometry = track.positions_size() == 1 ? "Point" : "LineString";
  out << "<Placemark>\n<name>node " << src << "</name>\n<" << geometry << ">\n"
      << "<altitudeMode>absolute</altitudeMode>\n<coordinates>\n";
  write_kml_coordinates({track.positions().begin(), track.positions().end()}, out);
  out << "</coordinates>\n</" << geometry << ">\n</Placemark>\n</Document>\n</kml>\n";
}

void add_track_command(CLI::App& app, const GlobalOptions& global) {
  static TrackOptions options;
  CLI::App* track = app.add_subcommand("track", "A vehicle's track, received as position telemetry");
  track->add_option("SRC", options.src, "The vehicle's modem id")->required()->type_name("SRC");
  track->add_option("--since", options.since, "From this time (default: the beginning)")->type_name("T");
  auto* csv = track->add_flag("--csv", options.csv, "CSV on stdout: time,x,y,z,lat,lon,depth,full (the default)");
  track->add_option("--kml", options.kml, "Write a KML file (Google Earth) instead")
      ->type_name("FILE")
      ->excludes(csv);
  track->footer(
      "Every position reconstructed from SRC's telemetry stream, oldest first, one per tau. T is seconds "
      "since the Unix epoch, \"now\", or -30s, -10m, -2h, -1d.\n\n"
      "Examples:\n"
      "  acommsctl track 2 --since -1h --csv > auv2.csv\n"
      "  acommsctl track 2 --kml auv2.kml");
  track->callback([&global] { run_track(global, options); });
}

}  // namespace acomms::cli
