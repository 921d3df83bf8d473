#pragma once
// The model's prediction for each packet a real modem hears (issue "the
// model meets the sea"): the TL that GRAM's environment gives between the
// two modems and the SNR the sonar equation predicts, SL − TL − NL, put in
// the packet event beside the SNR the modem measured ($CACST), so that
// `acommsctl link calibrate` can compare them (eval/link_calibration.h).
//
// Problem: the simulator knows both positions and its own physics; a real
// modem knows neither. The daemon knows its own position (the navigation
// input), the others' from their telemetry (node/modem_positions.h) or, for
// a node that does not move, from the config; it has the environment the
// vehicle knows (gram.base and its CTD casts) and the model's worker pool.
// The model is far too slow for the core thread, and a packet's event is
// written at once.
//
// Decision (the simulator's, sim_physics.h): one TL grid with this node as
// the source (reciprocity), over every depth and ranges 0..max_range_m,
// computed on GRAM's pool, asked again when this node's depth moved more
// than depth_tolerance_m or the environment changed; every packet reads the
// grid at the sender's range and depth. Until the first grid arrives (and
// when a position is missing or stale, the sender is beyond the grid, or
// GRAM has no environment) the packet gets no prediction: calibrate counts
// it as skipped, never as a guess. NL is the configured level or the noise
// model's band level at the environment's frequency; the site's correction
// (excess loss, own-ship noise) is left out: it is what calibrate measures.
//
// Core thread only (predict and the grid's arrival, posted there).

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "acomms/drivers/micromodem.pb.h"
#include "acomms/gram/environment.pb.h"
#include "acomms/v1/link_figures.pb.h"
#include "acomms/v1/modem_transmission.pb.h"
#include "core/node_position.h"
#include "gram/transmission_loss.h"
#include "node/modem_positions.h"

namespace acomms::gram {
class ModelPool;
class VehicleEnvironment;
}  // namespace acomms::gram

namespace acomms::node {

struct PredictionSources {
  int32_t own_id = 0;
  const core::NodePosition* own = nullptr;      // the navigation input
  const ModemPositions* others = nullptr;       // telemetry received
  gram::VehicleEnvironment* environment = nullptr;
  gram::ModelPool* pool = nullptr;
  std::function<void(std::function<void()>)> to_core;  // runs a task on the core thread later
  std::function<double()> now_s;                        // seconds since the epoch
};

class LinkPrediction : public std::enable_shared_from_this<LinkPrediction> {
 public:
  // Throws std::invalid_argument naming driver.micromodem.prediction.<field>
  // and its bound.
  static std::shared_ptr<LinkPrediction> create(const drivers::MicroModemPrediction& config,
                                                PredictionSources sources);

  // Sets figures.predicted_tl_db and predicted_snr_db for the packet
  // `heard` (from heard.src()) when it can; else leaves them unset.
  void predict(const v1::ModemTransmission& heard, v1::LinkFigures& figures);

  struct Counters {
    uint64_t predicted = 0;
    uint64_t no_position = 0;     // a position missing or stale
    uint64_t no_model = 0;        // no grid yet, no environment, or the model failed
    uint64_t out_of_range = 0;    // beyond max_range_m, or in a shadow
    uint64_t grids = 0;           // grids received
    uint64_t grid_requests = 0;   // model runs asked for
    uint64_t water_resolved = 0;  // GRAM's environment resolved (once per its version)
  };
  const Counters& counters() const { return counters_; }

 private:
  LinkPrediction() = default;
  std::optional<core::NodeFix> position_of(int32_t modem, bool own) const;
  // GRAM's environment as the grid takes it (source and receivers
  // cleared), resolved and serialized once per VehicleEnvironment version,
  // not for every packet heard (the hot path: predict runs per packet on
  // the core thread; resolving copies the environment under GRAM's lock and
  // serializing it costs more than the rest of predict together).
  struct Water {
    uint64_t version = 0;
    gram::Environment env;
    std::string bytes;    // env serialized: the key of a grid and of a failure
    double top_m = 0, bottom_m = 0;
    std::string problem;  // not empty: this version gives no grid
  };
  const Water& water();
  struct GridRequest {
    gram::Environment env;  // source at this node's depth, receivers set
    std::string water;      // Water::bytes it came from
  };
  // The grid's environment for this node at `depth_m`, when a new grid is
  // due; else nullopt (the reason logged once when there is a problem).
  std::optional<GridRequest> grid_environment(double own_depth_m);
  void follow(double own_depth_m);
  double model_depth(double z_up) const;

  drivers::MicroModemPrediction config_;
  PredictionSources sources_;
  double source_level_db_ = 190, max_range_m_ = 5000, range_step_m_ = 10, depth_tolerance_m_ = 1;
  double max_age_s_ = 600;
  std::map<int32_t, core::NodeFix> fixed_;

  // The grid in use and what it was computed for.
  std::shared_ptr<const gram::TransmissionLoss> grid_;
  double grid_depth_m_ = 0, grid_noise_db_ = 0, top_m_ = 0, bottom_m_ = 0;
  std::optional<Water> water_;  // the environment last resolved
  std::string grid_water_;      // the environment it came from (Water::bytes)
  bool pending_ = false;
  std::string failed_water_;    // the model or the environment refused this one: not asked again
  double failed_depth_m_ = -1;
  std::string last_problem_;    // logged once
  Counters counters_;
};

}  // namespace acomms::node
