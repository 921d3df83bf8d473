#pragma once
// `acommsctl track SRC`: the positions this daemon reconstructed from a
// vehicle's telemetry stream, as CSV or as a KML file for Google Earth.

#include <CLI/CLI.hpp>

#include <ostream>

#include "acomms/v1/acomms.pb.h"

namespace acomms::cli {

struct GlobalOptions;

void add_track_command(CLI::App& app, const GlobalOptions& options);

// time,x,y,z,lat,lon,depth,full (lat/lon empty without a datum).
void write_track_csv(const v1::TrackResponse& track, std::ostream& out);
// One Placemark with the track as a LineString (lon,lat,-depth; a Point for
// a single position); no track: a Document with no Placemark whose
// description says so. Throws UsageError when the positions have no
// lat/lon (no datum configured).
void write_track_kml(const v1::TrackResponse& track, int32_t src, std::ostream& out);

}  // namespace acomms::cli
