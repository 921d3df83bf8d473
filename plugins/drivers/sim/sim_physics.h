#pragma once
// The simulator's physics (sim.proto SimPhysics): whether a packet from
// another node decodes here, from SNR = SL − TL − NL and the rate's
// reception curve (gram/link_physics.h), TL from the built-in model.
//
// Problem: the model is far too slow for the core thread, yet every packet
// needs a TL now. Decision: one TL grid per node, with the node itself as
// the source (reciprocity: the same loss both ways), over every depth and
// ranges 0..max_range_m; every pair involving this node reads its TL from
// it at the sender's range and depth. The grid is asked for (through a
// TlGridSource, off the core thread) at start and again whenever this
// node's depth has moved more than depth_tolerance_m from the grid's
// source depth; until the new one arrives the last one is used, so the
// link never waits. Delay spread needs the arrivals at the sender's exact
// position: asked per sender in the same way, reported from the last answer.
// A node within 1 m of the surface or the bottom is modelled 1 m inside:
// the model has no field on a boundary.
// Thread rules: everything on the core thread; answers come back there.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>

#include "acomms/drivers/sim.pb.h"
#include "acomms/gram/environment.pb.h"
#include "gram/link_physics.h"
#include "sim/sim_envelope.h"
#include "sim/tl_grid_source.h"

namespace acomms::drivers {

class SimPhysics : public std::enable_shared_from_this<SimPhysics> {
 public:
  // Reads env_file. Throws std::invalid_argument naming
  // driver.sim.physics.<field> and the bound.
  static std::shared_ptr<SimPhysics> create(const SimPhysicsConfig& config, int32_t own_id);

  void set_source(std::shared_ptr<TlGridSource> source) { source_ = std::move(source); }
  bool has_source() const { return source_ != nullptr; }

  // Asks for a new grid if this node's depth left the current (or pending)
  // grid's tolerance, or if there is none.
  void follow(const SimPosition& own);

  struct Judgement {
    bool modelled = false;  // false: no grid has arrived yet
    double range_m = 0;     // horizontal
    double tl_db = 0, snr_db = 0, probability = 0;
    // What the model alone predicts, without the site's correction:
    // SL − TL − NL_ambient (acommsctl link calibrate compares snr_db,
    // the "measured" SNR, with it).
    double predicted_snr_db = 0;
    std::optional<double> delay_spread_s;
  };
  Judgement judge(int32_t sender, const SimPosition& from, const SimPosition& own, int32_t rate);

  // The source depth of the grid in use (nullopt before the first).
  std::optional<double> grid_depth_m() const;
  uint64_t grids_received() const { return grids_received_; }
  double noise_level_db() const { return physics_.noise_level_db; }
  const gram::LinkPhysics& link_physics() const { return physics_; }

 private:
  SimPhysics() = default;
  double model_depth(const SimPosition& p) const;  // −z, kept 1 m inside the water
  void ask_grid(double depth_m);
  void on_grid(double depth_m, ModelAnswer answer);
  void ask_spread(int32_t sender, double range_m, double sender_depth_m, double own_depth_m);

  struct Spread {
    std::optional<double> delay_spread_s;
    double range_m = -1, sender_depth_m = 0, own_depth_m = 0;  // where it was asked
    bool pending = false;
  };

  int32_t own_id_ = 0;
  gram::Environment environment_;  // the water, without source or receivers
  gram::LinkPhysics physics_;
  double max_range_m_ = 5000, range_step_m_ = 10, depth_step_m_ = 2, depth_tolerance_m_ = 1;
  double top_m_ = 0, bottom_m_ = 0;
  std::shared_ptr<TlGridSource> source_;
  std::shared_ptr<const gram::TransmissionLoss> grid_;
  double grid_depth_m_ = 0;
  std::optional<double> pending_depth_m_;
  std::optional<double> failed_depth_m_;  // the model refused it: not asked again
  std::optional<SimPosition> last_own_;  // re-checked when an answer arrives
  uint64_t grids_received_ = 0;
  std::map<int32_t, Spread> spreads_;
};

}  // namespace acomms::drivers
