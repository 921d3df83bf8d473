#pragma once
// One of the node's links, assembled: its supervised driver, its MAC, the
// LinkController that binds them to the node's queues, its raw log, and
// the depth rule that enables it (LinkConfig.enable_above_depth_m).
//
// Why a class of its own: a node holds several links (an acoustic modem, a
// satellite modem, a UDP tether), each with the same parts built the same
// way from its LinkConfig, and each failing on its own: every link has its
// own DriverSupervisor, so a driver that fails restarts without touching
// another link. What links share (the queues, the choice of link) is
// given to each.
//
// Invariant: built in dependency order (driver, MAC, controller) and
// destroyed in reverse; the controller is stopped on the core thread
// before destruction (the Daemon does it). Core thread only once started.

#include <map>
#include <memory>
#include <optional>
#include <string>

#include "acomms/v1/config.pb.h"
#include "core/event_loop.h"
#include "core/node_position.h"
#include "core/scheduler.h"
#include "link/depth_switch.h"
#include "link/driver_registry.h"
#include "link/driver_supervisor.h"
#include "link/link_choice.h"
#include "link/link_controller.h"
#include "link/raw_log.h"
#include "mac/mac.h"
#include "node/link_prediction.h"
#include "node/modem_positions.h"
#include "queue/queue_manager.h"

namespace acomms::gram {
class ModelPool;
class VehicleEnvironment;
}

namespace acomms::node {

// What every link of a node is built with; all outlive the links.
struct LinkParts {
  int32_t own_id;
  std::string data_dir;                 // where raw logs go
  int link_count;                       // raw log names: "link-raw.log" when 1
  core::Scheduler& scheduler;  // the AsioScheduler; a test's SimulatedScheduler
  core::EventLoop& core;
  const link::DriverRegistry& drivers;
  const core::NodePosition& node_position;
  gram::ModelPool* models;
  queue::QueueManager& queues;
  link::LinkChoice& choice;
  link::LinkController::Deliver deliver;
  std::function<void(std::function<void()> then)> after_receipt_durable;
  // The model's prediction for packets a real modem hears
  // (node/link_prediction.h): the others' positions and GRAM's environment.
  const ModemPositions* modem_positions = nullptr;
  gram::VehicleEnvironment* environment = nullptr;
};

class NodeLink {
 public:
  // Builds link `index` (config order). Throws std::runtime_error naming the
  // link for a configuration mistake (unknown driver, bad driver block, bad
  // cycle); device failures later are the supervisor's to retry.
  NodeLink(const v1::LinkConfig& config, int index, LinkParts& parts);
  ~NodeLink();
  NodeLink(const NodeLink&) = delete;
  NodeLink& operator=(const NodeLink&) = delete;

  const std::string& name() const { return config_.name(); }
  const v1::LinkConfig& config() const { return config_; }
  link::DriverSupervisor& driver() { return *driver_; }
  mac::Mac& mac() { return *mac_; }
  link::LinkController& controller() { return *controller_; }
  // Null unless driver.micromodem.prediction is set.
  const LinkPrediction* prediction() const { return prediction_.get(); }

  // When this link last delivered a message from `src` (host seconds) and
  // at which rate; nullopt if never. Core thread.
  struct Heard {
    double time_s = 0;
    int32_t rate = 0;
  };
  std::optional<Heard> last_heard(int32_t src) const;
  // A packet from `src` sent on this link and not received, known only from
  // a telemetry gap (node/unheard_packets.h): a packet event, not decoded,
  // at the rate last heard from it, without measured figures, with the
  // model's prediction when this link has one. Core thread.
  void record_unheard(int32_t src);

  // A navigation fix's depth (m, down): enables or disables the link when
  // it crosses enable_above_depth_m (link/depth_switch.h). Core thread.
  void on_depth(double depth_m);

 private:
  v1::LinkConfig config_;
  std::unique_ptr<link::DriverSupervisor> driver_;
  std::unique_ptr<mac::Mac> mac_;
  std::unique_ptr<link::RawLog> raw_log_;  // outlives controller_, which writes to it
  std::shared_ptr<LinkPrediction> prediction_;  // a Micro-Modem's, when configured
  std::unique_ptr<link::LinkController> controller_;
  std::optional<link::DepthSwitch> depth_;
  queue::QueueManager& queues_;
  int32_t own_id_;
  std::map<int32_t, Heard> heard_;  // by sender, from what this link delivered
};

}  // namespace acomms::node
