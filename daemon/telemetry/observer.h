#pragma once
// A state observer: what both ends of a telemetry stream run to predict the
// next sample from the samples sent so far (Schneider 2013, section 3.3).
//
// The observer is fed only with what the receiver also has: the position of
// a full transmission that re-anchors the stream (reset) and each
// reconstructed sample after it (update; a full that a delta could have
// carried is such a sample too), all on the precision grid. Its prediction is rounded to that grid
// before anything is compared, so the innovation dy = y - prediction is an
// integer and both ends agree on it bit for bit (deterministic_math.h).

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "telemetry/telemetry_config.h"

namespace acomms::telemetry {

// A position on the precision grid: metres / precision, rounded.
using GridPosition = std::array<int64_t, kAxes>;

struct Prediction {
  GridPosition position{};
  // The observer's variance of each axis, in precision steps squared (what
  // the Gaussian models take as sigma^2).
  std::array<double, kAxes> variance{};
};

class Observer {
 public:
  virtual ~Observer() = default;
  // Starts over from a full transmission's position.
  virtual void reset(const GridPosition& position) = 0;
  // The prior for the next sample (tau after the last one).
  virtual Prediction predict() = 0;
  // The next sample, as both ends reconstructed it.
  virtual void update(const GridPosition& position) = 0;
  // The state after the last reset or update as bytes, and back (the
  // stream's durable state, stream_history.h): exact, doubles by their
  // bits, read back by the node that wrote them. load is false, and
  // changes nothing, for bytes of another observer or length.
  virtual std::string save() const = 0;
  virtual bool load(std::string_view bytes) = 0;
};

std::unique_ptr<Observer> make_observer(const TelemetryConfig& config);

}  // namespace acomms::telemetry
