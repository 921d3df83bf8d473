#pragma once
// Connects one node's driver, MAC and queues: the MAC's slots become
// transmissions, the driver's data requests are filled by the queues,
// received frames are split into messages for the subscribers, and ACKs
// clear what they acknowledge. Runs on the core thread.
//
// A data request asks the queues for no more frames than fit in what is
// left of the slot (link/slot_budget.h, with the driver's timing): a packet
// that outruns its slot is lost by a half-duplex neighbour whose own slot
// has begun. A request that answers a poll (one the MAC did not start) is
// dated from the poll's arrival (transmission_rules.h), later than the
// master's slot start by the poll's travel: the budget takes one more
// travel guard off what is left. A request with no slot (slot_seconds
// unset: a satellite modem's driver that holds a session when it decides,
// under MAC "none") is not budgeted: it gets what the driver asks for.
//
// A node with several links has one controller per link, sharing the
// queues and the node's choice of link (link_choice.h): each asks the
// queues for what its link may carry, under its own index, and tells the
// choice when it hears a node. A link can be disabled and enabled at run
// time (set_enabled): disabled, its MAC and driver are stopped.

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <tuple>
#include <string_view>
#include <vector>

#include "acomms/v1/link_figures.pb.h"
#include "acomms/v1/modem_transmission.pb.h"
#include "core/clock.h"
#include "link/driver.h"
#include "link/driver_specific_gate.h"
#include "link/link_choice.h"
#include "link/slot_budget.h"
#include "mac/mac.h"
#include "queue/queue_manager.h"

namespace acomms::link {

struct LinkStats {
  uint64_t transmissions_sent = 0;
  uint64_t transmissions_failed = 0;
  uint64_t data_received = 0;      // DATA transmissions heard (any destination)
  uint64_t acks_received = 0;      // ACKs for this node
  uint64_t messages_delivered = 0;
  uint64_t receptions_with_figures = 0;  // DATA that carried the modem's ReceptionFigures
  uint64_t bad_frames_received = 0;      // frames those packets lost (figures.bad_frames)
};

struct LinkOptions {
  // Tells how much of its slot has gone when a data request comes (an
  // answer to a poll comes late in it). Null: requests are taken to come at
  // the start of their slot, as the MAC's own do.
  const core::Clock* clock = nullptr;
  // The farthest node (mac.max_range_m): the slot keeps the time sound
  // takes to get there (and back, for an ACK).
  double max_range_m = kDefaultMaxRangeM;
  // Runs the deadlines of driver-specific requests waiting for a slot
  // (null: checked when the slot comes).
  core::Scheduler* scheduler = nullptr;
  // Given to the driver (DriverCallbacks::after_receipt_durable): software
  // ACKs wait until the queues' received events are committed, and, on a
  // gateway, only go if the custody they imply was taken (queue/routing.h).
  // Null: at once, custody or not.
  std::function<void(std::function<void()> then)> after_receipt_durable;
  // A node with several links: the choice of link they share (outliving the
  // controller) and this link's index in it; also the queues' link index
  // (DataRequest::link). Null: one link, which carries everything.
  LinkChoice* choice = nullptr;
  int link_index = 0;
  // Whether start() really starts the link (LinkConfig.enabled).
  bool enabled = true;
  // Fills the model's prediction (predicted_tl_db, predicted_snr_db) into
  // the figures of a packet heard from `transmission.src()`, when the
  // driver gave none (a real modem: node/link_prediction.h). Core thread.
  // Null: packet events carry what the driver gave.
  std::function<void(const v1::ModemTransmission& transmission, v1::LinkFigures& figures)> predict;

  // From the config (mac.max_range_m, unset: kDefaultMaxRangeM) and the
  // core's clock.
  static LinkOptions from_config(const v1::MacConfig& mac, const core::Clock& clock);
};

class LinkController {
 public:
  // Called for every received message meant for this node.
  using Deliver = std::function<void(queue::ReceivedMessage message, const v1::ModemTransmission& from)>;

  // All references must outlive the controller.
  LinkController(int32_t own_id, queue::QueueManager& queues, mac::Mac& mac, Driver& driver, Deliver deliver,
                 LinkOptions options = {});

  // Starts the driver, then the MAC. Throws what the driver's start throws.
  void start();
  // Stops the MAC, then the driver.
  void stop();
  // Enables or disables the link between start() and stop(): disabled,
  // its MAC and driver are stopped, and what awaited an ACK on it may go
  // on another link. Idempotent; returns false when it changed nothing.
  bool set_enabled(bool enabled);
  bool enabled() const { return enabled_; }
  // The supervised driver started (up) or failed or stopped (down): what
  // awaited an ACK on this link may go on another one.
  void on_driver_state(bool up);

  const LinkStats& stats() const { return stats_; }
  // Messages from `src` to this node (or broadcast) that this link's
  // packet events already tell were lost, since the start: a packet heard
  // and not decoded (the driver's on_reception_failed, or every frame bad)
  // counts its bad frames, at least one; a decoded packet with bad frames
  // (a PSK packet whose first frame failed) counts those. Packets
  // overheard between other nodes are not counted. A telemetry gap counts
  // only the losses this link did not already record
  // (node/unheard_packets.h). Core thread.
  uint64_t lost_recorded(int32_t src) const {
    auto it = lost_recorded_.find(src);
    return it == lost_recorded_.end() ? 0 : it->second;
  }
  // A driver-specific transmission (link/driver_specific.h): checked by the
  // driver now, then sent when the channel is this node's (the slot rule:
  // link/driver_specific_gate.h); `done` runs exactly once.
  // `timeout_s` from now covers the wait and the exchange.
  void request_driver_specific(const v1::ModemTransmission& request, double timeout_s, DriverSpecificDone done);
  // Every chunk of bytes to (outgoing) and from the device, as the driver
  // reports it (the raw link log). Set before start().
  void set_raw_tap(std::function<void(std::string_view bytes, bool outgoing)> tap) { raw_tap_ = std::move(tap); }

 private:
  // Starts (stops) the driver, then (before) the MAC.
  void run();
  void halt();
  double now_s() const { return options_.clock == nullptr ? 0 : options_.clock->now_seconds(); }
  void on_data_request(v1::ModemTransmission* transmission);
  // max_num_frames capped by what fits in the rest of the slot.
  uint32_t frames_for_slot(const v1::ModemTransmission& transmission);
  void on_receive(const v1::ModemTransmission& transmission);
  // A received DRIVER_SPECIFIC: each extension message set goes to the
  // subscribers as a message of its own type (not kept in the store).
  void deliver_driver_specific(const v1::ModemTransmission& transmission);
  // A "packet" event for a packet from another node that came with figures
  // (measured and, when the driver has it, predicted SNR), decoded or not:
  // the field data acommsctl link calibrate fits.
  void record_packet(const v1::ModemTransmission& transmission, bool decoded);
  void on_transmit_result(const v1::ModemTransmission& transmission, bool ok, const std::string& error);

  int32_t own_id_;
  queue::QueueManager& queues_;
  mac::Mac& mac_;
  Driver& driver_;
  Deliver deliver_;
  LinkOptions options_;
  bool in_own_slot_ = false;  // the MAC's transmission is being started
  bool started_ = false;      // between start() and stop()
  bool enabled_ = true;
  bool running_ = false;      // started_ and enabled_: driver and MAC run
  // Slot shapes (src, rate, seconds) already warned about as too short.
  std::set<std::tuple<int32_t, int32_t, double>> short_slots_warned_;
  // Queue frame ids of the last DATA transmission to each destination, by
  // frame index: an ACK names indices, the queues know frame ids.
  std::map<int32_t, std::vector<uint64_t>> awaiting_ack_;
  LinkStats stats_;
  std::map<int32_t, uint64_t> lost_recorded_;  // by sender
  std::function<void(std::string_view, bool)> raw_tap_;
  DriverSpecificGate gate_;
  // A poll was answered with a blank frame so that a waiting extra can
  // follow it: sent at that answer's result.
  bool extra_after_poll_answer_ = false;
  // Custody conditions of the DATA just received (queue/routing.h),
  // applied to its ACK.
  std::vector<std::shared_ptr<std::atomic<bool>>> ack_conditions_;
};

}  // namespace acomms::link
