#pragma once
// "sim": an acoustic modem simulator, so that the MAC, the queues and whole
// multi-vehicle missions can be exercised without water.
//
// Physics, worked out by each receiving node from the sender's envelope:
//  - Delay: sound leaves the sender at `start` and reaches a node at range r
//    after r / c (c = sim.sound_speed, 1500 m/s by default). The packet is
//    in the water for its air time (link/rate_table.h), so a receiver has it
//    from start + r/c to start + r/c + air time, and reports it at the end.
//  - Loss: two independent causes. A fixed chance p (sim.loss_probability)
//    and a range-dependent one, r / sim.max_range_m (reaching 1 at that
//    range; none when max_range_m is 0). A packet survives only if it
//    survives both: P(loss) = 1 - (1 - p) (1 - min(1, r / max_range)).
//    A packet is lost or heard whole (frames are not lost one by one).
//  - Half-duplex: a node hears nothing while it transmits. A packet whose
//    arrival overlaps any of the node's own transmissions is lost at that
//    node, including one that began while it was transmitting (a modem
//    that missed a packet's start cannot lock on to it afterwards).
//  - Collisions: two packets whose arrivals overlap at a node destroy each
//    other there (and only there: elsewhere they may arrive apart).
//  Half-duplex and collision losses are counted (counters(), LinkStatus)
//  and logged once per burst: the first loss, and, when a packet next
//  arrives intact, how many were lost meanwhile.
// Timing for the slot budget (link/slot_budget.h) is exact, not estimated:
// the rate table's air time, kTurnaround plus a mini-packet for an ACK, and
// the configured sound speed.
// Protocol, as driver.h asks, run by link::DriverSequence: DATA addressed to
// this node with ack_requested is answered after a turnaround (kTurnaround)
// with a software ACK listing all its frames, itself a packet subject to the
// same physics; a poll (a request whose src is another node) is a short
// mini-packet, and the polled node answers it after the turnaround with a
// data request and its own DATA. A node is busy while it transmits: the
// MAC's transmission then fails ("busy"); ACKs and poll answers wait.
//
// Two channels:
//  - in process: nodes share a SimChannel (usually on one SimulatedScheduler;
//    deterministic with the channel's or the config's seed);
//  - loopback: nodes in separate processes, in real time, exchanging
//    envelopes over UDP (sim.listen, sim.peers) on the core io_context.
// With neither (no channel, empty sim.listen) the node is alone: its
// transmissions go out and nobody hears them.
//
// With sim.physics (sim_physics.h) a packet that survives the losses above
// also has to decode: it does with the probability its modelled SNR gives
// (SL − TL − NL, TL from the built-in model for the two nodes' range and
// depths), one draw per packet. The model runs on a TlGridSource, never on
// the core thread: a loopback or lone node makes its own (a worker thread,
// answers posted to its io_context); nodes on a SimChannel are given one
// (set_tl_grid_source, before start). Each modelled packet's figures carry
// the model's own prediction beside the SNR the site's correction gives
// (predicted_tl_db, predicted_snr_db), and a packet that failed its draw is
// told to on_reception_failed, so the link can be calibrated back from the
// event log (acommsctl link calibrate). The node's position comes from a
// NodePositionSource when one is set (its navigation), else from the config.

#include <asio/io_context.hpp>

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <unordered_set>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "core/scheduler.h"
#include "link/driver.h"
#include "link/driver_sequence.h"
#include "link/rate_table.h"
#include "sim/sim_channel.h"
#include "sim/sim_envelope.h"
#include "sim/node_position_source.h"
#include "sim/sim_medium.h"
#include "sim/sim_physics.h"

namespace acomms::gram {
class ModelPool;
}
#include "sim/tl_grid_source.h"

namespace acomms::drivers {

// Time from the end of a received packet to the start of the answer (ACK,
// poll response): the Micro-Modem's (link/rate_table.h).
inline constexpr std::chrono::milliseconds kTurnaround = link::kTurnaround;

struct SimStats {
  uint64_t sent = 0;              // packets this node put in the water
  uint64_t heard = 0;             // envelopes from other nodes
  uint64_t received = 0;          // packets that arrived intact
  uint64_t lost_random = 0;       // lost to the loss draw (fixed or range)
  uint64_t lost_collision = 0;    // destroyed by an overlapping packet
  uint64_t lost_half_duplex = 0;  // arrived while this node transmitted
  uint64_t lost_no_model = 0;     // physics: heard before the first TL grid arrived
  uint64_t garbage = 0;           // malformed loopback datagrams dropped
};

class SimDriver final : public link::Driver {
 public:
  // In process: the node joins `channel` when started.
  SimDriver(const v1::DriverConfig& config, core::Scheduler& scheduler, std::shared_ptr<SimChannel> channel);
  // Loopback (config.sim.listen set; needs `io_context`) or alone.
  // With physics, the model runs on `models` (GRAM's pool) when given, else
  // on a worker thread of the driver's own.
  SimDriver(const v1::DriverConfig& config, core::Scheduler& scheduler, asio::io_context* io_context,
            gram::ModelPool* models = nullptr);
  ~SimDriver() override;

  void start(link::DriverCallbacks callbacks) override;
  void stop() override;
  void do_work() override;
  void initiate_transmission(const v1::ModemTransmission& transmission) override;
  std::chrono::nanoseconds packet_air_time(int32_t rate, uint32_t num_frames) const override;
  std::chrono::nanoseconds ack_time(int32_t rate) const override;
  double sound_speed() const override { return sound_speed_; }
  link::DriverCounters counters() const override;

  int32_t modem_id() const { return id_; }
  // Where the node is now: its position source's, else the config's (or
  // the last set_position()).
  SimPosition position() const { return position_source_ ? position_source_->position() : position_; }
  // Moves the node (a vehicle under way); later transmissions see it there.
  void set_position(const SimPosition& position) { position_ = position; }
  // Takes the position from `source` from now on (null: back to the config's).
  void set_position_source(std::shared_ptr<const NodePositionSource> source) { position_source_ = std::move(source); }
  // Where model runs go (physics only). Replaces the node's own worker.
  void set_tl_grid_source(std::shared_ptr<TlGridSource> source);
  // The physics (null without sim.physics), for status and tests.
  const SimPhysics* physics() const { return physics_.get(); }
  const SimStats& stats() const;
  // Loss probability at range `range_m` (see the file comment).
  double loss_probability(double range_m) const;
  // The loopback port when listening (after start; 0 otherwise).
  uint16_t listen_port() const;

 private:
  struct Interval {
    core::Clock::time_point start, end;
  };
  struct Arrival {
    Interval interval;
    SimEnvelope envelope;
    double range_m = 0;
    bool collided = false;
    bool deaf = false;  // overlapped one of our transmissions
    std::optional<SimPhysics::Judgement> judgement;  // physics only
  };

  SimDriver(const v1::DriverConfig& config, core::Scheduler& scheduler, std::unique_ptr<SimMedium> medium,
            uint32_t default_seed);

  // Whether a packet that survived the other losses decodes (physics);
  // fills the figures of `arrival` for deliver().
  bool decodes(Arrival& arrival);

  void hear(const SimEnvelope& envelope);
  void finish_arrival(uint64_t key);
  void deliver(const Arrival& arrival);
  // A modelled packet that failed its draw: told to on_reception_failed
  // with the model's prediction, so that a calibration counts it.
  void report_failed(const Arrival& arrival);
  // The rate whose reception curve judges `tx` (mini-packets: 0).
  static int32_t curve_rate(const v1::ModemTransmission& tx);
  static void set_prediction(const SimPhysics::Judgement& j, v1::ReceptionFigures* figures);
  // A packet lost to half-duplex or a collision: logged if it begins a burst.
  void note_lost(const Arrival& arrival, const char* why);
  // The sequence's Medium::send: puts a packet in the water now (DATA with
  // frames for its air time at the rate, anything else as a mini-packet);
  // "" or why not ("busy").
  std::string transmit(v1::ModemTransmission transmission, bool report);
  // ACKs and poll answers: at `when`, or once we stop transmitting.
  void send_when_free(core::Clock::time_point when, std::function<void()> send);
  core::Scheduler::TaskId schedule(core::Clock::time_point when, std::function<void()> task);
  double uniform();

  int32_t id_;
  SimPosition position_;
  double sound_speed_;
  double loss_probability_;
  double max_range_m_;
  core::Scheduler& scheduler_;
  std::unique_ptr<SimMedium> medium_;
  std::shared_ptr<const NodePositionSource> position_source_;
  std::shared_ptr<SimPhysics> physics_;  // shared: model answers hold it weakly
  std::mt19937_64 rng_;
  link::DriverSequence sequence_;  // holds the callbacks between start() and stop()
  core::Clock::time_point busy_until_;
  std::vector<Interval> own_transmissions_;  // recent, for half-duplex
  std::map<uint64_t, Arrival> arrivals_;     // packets on their way to us
  uint64_t next_arrival_ = 1;
  uint64_t lost_in_burst_ = 0;  // half-duplex and collision losses since a packet last arrived
  std::unordered_set<core::Scheduler::TaskId> tasks_;
  mutable SimStats stats_;
};

}  // namespace acomms::drivers
