#pragma once
// KML 2.2 for Google Earth, in one home: the coordinates of a track (used by
// `acommsctl track --kml` and by `geov serve`), the fleet's live document,
// its history with time stamps, and the NetworkLink that refreshes the live
// one.
//
// Coordinates are lon,lat,altitude (KML's order) with altitude = -depth,
// metres above sea level, altitudeMode absolute. Positions without lat/lon
// (a daemon with no telemetry.datum) cannot be placed on the Earth: callers
// check kml_placeable() first and say so.
//
// Thread-safety: pure functions.

#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "acomms/telemetry/position.pb.h"

namespace acomms::cli {

using VehicleTracks = std::map<int32_t, std::vector<telemetry::Position>>;

// "%.10g", never "-0".
std::string kml_number(double value);
// "2026-11-27T01:02:03Z" (with milliseconds when the time has a fraction).
std::string kml_time(double unix_seconds);
// One "lon,lat,alt\n" line per position.
void write_kml_coordinates(const std::vector<telemetry::Position>& positions, std::ostream& out);
// True when every position has lat/lon.
bool kml_placeable(const VehicleTracks& tracks);

// Each vehicle's last position (a Point, named with its depth and time) and
// its track (a LineString), for the NetworkLink to refresh.
void write_fleet_live_kml(const VehicleTracks& tracks, std::ostream& out);
// Per vehicle a Folder: the track as a LineString spanning its TimeSpan,
// and every position as a Placemark with its TimeStamp, so Google Earth's
// time slider plays the fleet back.
void write_fleet_history_kml(const VehicleTracks& tracks, const std::string& title, std::ostream& out);
// A NetworkLink to `href` refreshed every `refresh_s` seconds.
void write_network_link_kml(const std::string& href, double refresh_s, std::ostream& out);

}  // namespace acomms::cli
