#include "telemetry/datum.h"

#include <GeographicLib/LocalCartesian.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

namespace acomms::telemetry {

void check_latlon(const LatLon& at, const char* what) {
  if (!std::isfinite(at.lat) || at.lat < -90 || at.lat > 90)
    throw std::invalid_argument(std::string(what) + ".lat " + std::to_string(at.lat) + " must be within [-90, 90]");
  if (!std::isfinite(at.lon) || at.lon < -180 || at.lon > 180)
    throw std::invalid_argument(std::string(what) + ".lon " + std::to_string(at.lon) +
                                " must be within [-180, 180]");
}

Datum::Datum(double lat, double lon, double height_m) : height_m_(height_m) {
  check_latlon(LatLon{lat, lon}, "telemetry.datum");
  if (!std::isfinite(height_m)) throw std::invalid_argument("telemetry.datum.height_m must be finite");
  frame_ = std::make_unique<GeographicLib::LocalCartesian>(lat, lon, height_m);
}

Datum::~Datum() = default;
Datum::Datum(Datum&&) noexcept = default;
Datum& Datum::operator=(Datum&&) noexcept = default;

LocalXY Datum::to_local(const LatLon& at) const {
  LocalXY out;
  double z = 0;
  frame_->Forward(at.lat, at.lon, height_m_, out.x, out.y, z);
  return out;
}

LatLon Datum::to_latlon(const LocalXY& at) const {
  LatLon out;
  double h = 0;
  // The point on the tangent plane at x, y; its height above the
  // ellipsoid is not used (see the header).
  frame_->Reverse(at.x, at.y, 0, out.lat, out.lon, h);
  return out;
}

}  // namespace acomms::telemetry
