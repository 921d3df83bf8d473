#include "kml.h"

#include <cmath>
#include <cstdio>
#include <ctime>

#include "geov/json_text.h"

namespace acomms::cli {
namespace {

const char* kHeader =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n<Document>\n";
const char* kFooter = "</Document>\n</kml>\n";

// One style per vehicle, the colour from a fixed list (aabbggrr).
const char* colour(int32_t src) {
  static const char* colours[] = {"ff0000ff", "ffff0000", "ff00aa00", "ff00aaff", "ffaa00aa", "ffaaaa00"};
  return colours[static_cast<unsigned>(src) % 6];
}

void write_style(int32_t src, std::ostream& out) {
  out << "<Style id=\"node" << src << "\"><LineStyle><color>" << colour(src)
      << "</color><width>2</width></LineStyle><IconStyle><color>" << colour(src) << "</color></IconStyle></Style>\n";
}

void write_line(const std::vector<telemetry::Position>& track, std::ostream& out) {
  out << "<LineString>\n<altitudeMode>absolute</altitudeMode>\n<coordinates>\n";
  write_kml_coordinates(track, out);
  out << "</coordinates>\n</LineString>\n";
}

void write_point(const telemetry::Position& p, std::ostream& out) {
  out << "<Point>\n<altitudeMode>absolute</altitudeMode>\n<coordinates>";
  out << kml_number(p.lon()) << ',' << kml_number(p.lat()) << ',' << kml_number(0.0 - p.depth());
  out << "</coordinates>\n</Point>\n";
}

}  // namespace

std::string kml_number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.10g", value == 0 ? 0.0 : value);
  return text;
}

std::string kml_time(double unix_seconds) {
  const double whole = std::floor(unix_seconds);
  const std::time_t seconds = static_cast<std::time_t>(whole);
  std::tm utc{};
  ::gmtime_r(&seconds, &utc);
  char text[40];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  std::string out = text;
  const int millis = static_cast<int>(std::lround((unix_seconds - whole) * 1000));
  if (millis > 0 && millis < 1000) {
    std::snprintf(text, sizeof text, ".%03d", millis);
    out += text;
  }
  return out + "Z";
}

void write_kml_coordinates(const std::vector<telemetry::Position>& positions, std::ostream& out) {
  // lon,lat,altitude: x before y, as KML orders them; altitude is metres
  // above sea level, so minus the depth.
  for (const telemetry::Position& p : positions)
    out << kml_number(p.lon()) << ',' << kml_number(p.lat()) << ',' << kml_number(0.0 - p.depth()) << '\n';
}

bool kml_placeable(const VehicleTracks& tracks) {
  for (const auto& [src, track] : tracks) {
    for (const telemetry::Position& p : track) {
      if (!p.has_lat() || !p.has_lon()) return false;
    }
  }
  return true;
}

void write_fleet_live_kml(const VehicleTracks& tracks, std::ostream& out) {
  out << kHeader << "<name>acomms fleet (live)</name>\n";
  for (const auto& [src, track] : tracks) write_style(src, out);
  for (const auto& [src, track] : tracks) {
    if (track.empty()) continue;
    const telemetry::Position& last = track.back();
    out << "<Placemark>\n<name>node " << src << "</name>\n<description>depth " << kml_number(last.depth())
        << " m at " << kml_time(last.time()) << "</description>\n<styleUrl>#node" << src << "</styleUrl>\n";
    write_point(last, out);
    out << "</Placemark>\n";
    if (track.size() < 2) continue;  // KML 2.2: a LineString needs two coordinates
    out << "<Placemark>\n<name>node " << src << " track</name>\n<styleUrl>#node" << src << "</styleUrl>\n";
    write_line(track, out);
    out << "</Placemark>\n";
  }
  out << kFooter;
}

void write_fleet_history_kml(const VehicleTracks& tracks, const std::string& title, std::ostream& out) {
  out << kHeader << "<name>" << geov::xml_text(title) << "</name>\n";
  for (const auto& [src, track] : tracks) write_style(src, out);
  for (const auto& [src, track] : tracks) {
    out << "<Folder>\n<name>node " << src << "</name>\n";
    if (track.size() >= 2) {
      out << "<Placemark>\n<name>node " << src << " track</name>\n<TimeSpan><begin>" << kml_time(track.front().time())
          << "</begin><end>" << kml_time(track.back().time()) << "</end></TimeSpan>\n<styleUrl>#node" << src
          << "</styleUrl>\n";
      write_line(track, out);
      out << "</Placemark>\n";
    }
    for (const telemetry::Position& p : track) {
      out << "<Placemark>\n<TimeStamp><when>" << kml_time(p.time()) << "</when></TimeStamp>\n<styleUrl>#node" << src
          << "</styleUrl>\n";
      write_point(p, out);
      out << "</Placemark>\n";
    }
    out << "</Folder>\n";
  }
  out << kFooter;
}

void write_network_link_kml(const std::string& href, double refresh_s, std::ostream& out) {
  out << kHeader << "<name>acomms fleet</name>\n<NetworkLink>\n<name>acomms fleet (live)</name>\n"
      << "<refreshVisibility>0</refreshVisibility>\n<flyToView>0</flyToView>\n<Link>\n<href>" << geov::xml_text(href)
      << "</href>\n<refreshMode>onInterval</refreshMode>\n<refreshInterval>" << kml_number(refresh_s)
      << "</refreshInterval>\n</Link>\n</NetworkLink>\n"
      << kFooter;
}

}  // namespace acomms::cli
