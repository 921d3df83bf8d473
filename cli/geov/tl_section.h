#pragma once
// The environment on the map (issue 33): for one vehicle, the transmission
// loss from the buoy towards it with its depth marked: the picture `gram tl
// --png` draws (gram_plot.h), of a section the daemon's model runs
// (acomms.v1.Gram TransmissionLoss on the environment it holds).
//
// The buoy is the followed daemon's own node: the source of its gram
// environment (its source_depth_m is the buoy modem's depth). Its place is
// its own last position when the map has one, else the telemetry datum
// (x = y = 0), where a buoy's daemon is normally configured to be.
//
// Bounds, because any viewer may ask, as often as it likes: one model run
// at a time for the whole server (a second viewer waits for it, then takes
// its picture), a receiver grid of kRanges x kDepths, a section at most
// kMaxSectionM long, a deadline on every call; a picture is reused for up
// to kReuseS while its vehicle has moved less than 2 % of its range and
// 2 m in depth; one picture kept per vehicle.
//
// Refusals are a status and one line (SectionRefusal): 503 when the daemon
// holds no environment (no sound speed: gram.base in its config, or `gram
// env update --ctd`), cannot be reached, or its model is busy; 504 when
// the run passed its deadline; 422 when the vehicle is beyond the longest
// section; 502 for any other refusal of the daemon (its message quoted).
//
// Thread-safety: picture() from any thread (one mutex, held through the
// run); plan_section() is a pure function.

#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "acomms/gram/known_environment.pb.h"
#include "acomms/telemetry/position.pb.h"
#include "fleet.h"
#include "global_options.h"

namespace acomms::cli::geov {

constexpr int kRanges = 121, kDepths = 61;
constexpr double kMaxSectionM = 50000, kMinSectionM = 200, kReuseS = 30;

struct SectionRefusal {
  int status;
  std::string text;
};

// A section's run: the environment sent (merged over the held one by the
// daemon) and the one the picture is drawn with (the held base with its
// newest profile instance, the request merged in as the daemon does).
struct SectionPlan {
  double range_m = 0;   // buoy to vehicle, horizontal
  double length_m = 0;  // the section's: a quarter past the vehicle, kMinSectionM at least
  gram::Environment request;
  gram::Environment drawn;
};

// Throws SectionRefusal (503 without sound speed, 422 beyond kMaxSectionM).
SectionPlan plan_section(const gram::KnownEnvironment& held, double range_m);

struct SectionPicture {
  std::string png;
  double range_m = 0;
};

class TlSection {
 public:
  // `daemon.endpoint` names the daemon whose environment and model are used.
  TlSection(GlobalOptions daemon, const Fleet& fleet);
  ~TlSection();
  // The picture towards `vehicle` (its last position). Throws SectionRefusal.
  SectionPicture picture(const telemetry::Position& vehicle);

 private:
  struct Kept {
    double x, y, depth, range_m, made_at;
    std::string png;
  };
  SectionPicture run(const telemetry::Position& vehicle);

  GlobalOptions daemon_;
  const Fleet& fleet_;
  std::mutex mutex_;
  std::map<int32_t, Kept> kept_;
};

}  // namespace acomms::cli::geov
