#pragma once
// The agreed origin of a telemetry stream's local metres: WGS84 lat/lon in,
// x east / y north out, and back (GeographicLib's LocalCartesian: exact on
// the ellipsoid, no hand-written projection to get wrong near the poles or
// far from the origin). z is not taken from the ellipsoid: telemetry's z is
// minus the depth the vehicle reports, so the local frame's vertical comes
// from the fix, not from the curvature of the earth (at 10 km from the
// datum the tangent plane is already 8 m above the sea surface).
//
// Thread-safe once built (const methods only).

#include <memory>

namespace GeographicLib {
class LocalCartesian;
}

namespace acomms::telemetry {

struct LatLon {
  double lat = 0;
  double lon = 0;
};

struct LocalXY {
  double x = 0;
  double y = 0;
};

class Datum {
 public:
  // Throws std::invalid_argument naming the bound for lat outside
  // [-90, 90] or lon outside [-180, 180] (or non-finite values).
  Datum(double lat, double lon, double height_m);
  ~Datum();
  Datum(Datum&&) noexcept;
  Datum& operator=(Datum&&) noexcept;

  LocalXY to_local(const LatLon& at) const;
  LatLon to_latlon(const LocalXY& at) const;

 private:
  std::unique_ptr<GeographicLib::LocalCartesian> frame_;
  double height_m_;
};

// Throws std::invalid_argument ("<what>.lat ... must be within [-90, 90]").
void check_latlon(const LatLon& at, const char* what);

}  // namespace acomms::telemetry
