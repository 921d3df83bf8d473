#pragma once
// One node of a whole network run in one process on the simulated clock:
// its own codec, queues (with an in-memory journal), MAC, sim driver on a
// shared SimChannel, and the link controller that binds them.
//
// The system tests (tests/system) each assembled this node by hand, in the
// same order and with the same parts; what differs between them is only
// the configuration (the types, the queue and MAC text), what a node does
// with what it receives, and sometimes a driver placed between the link
// controller and the sim driver (one that loses ACKs). Those are the
// arguments; the assembly is written once.
//
// Invariant: parts are built in dependency order and destroyed in reverse
// (the link controller first, the codec last), as in the daemon.
//
// Thread-compatible: like the daemon's core, everything runs on the thread
// that drives the SimulatedScheduler.

#include <functional>
#include <memory>
#include <string>

#include "acomms/v1/config.pb.h"
#include "core/scheduler.h"
#include "dccl/codec.h"
#include "link/driver.h"
#include "link/link_controller.h"
#include "mac/mac.h"
#include "queue/memory_journal.h"
#include "queue/queue_manager.h"
#include "sim/sim_channel.h"
#include "sim/sim_driver.h"

namespace acomms::testing {

struct SimNodeSetup {
  int32_t id = 0;
  double x = 0;                // position on the channel's x axis, m
  std::string proto;           // path of the .proto with the node's types
  std::string queue_config;    // v1::QueueConfig, protobuf text format
  std::string mac_config;      // v1::MacConfig, protobuf text format
  // LinkOptions::from_config(mac) as the daemon does, or the defaults.
  bool link_options_from_mac = false;
  // A driver between the link controller and the sim driver, or none.
  std::function<std::unique_ptr<link::Driver>(link::Driver& sim)> wrap_driver;
  // Changes to the sim driver's config before it is built (physics...), or none.
  std::function<void(v1::DriverConfig& config)> configure_driver;
};

class SimNode {
 public:
  SimNode(const SimNodeSetup& setup, core::SimulatedScheduler& scheduler,
          std::shared_ptr<drivers::SimChannel> channel, link::LinkController::Deliver deliver);
  virtual ~SimNode() = default;
  SimNode(const SimNode&) = delete;
  SimNode& operator=(const SimNode&) = delete;

  // Submits a `type` message given in text format (submit_now.h); the test
  // fails (non-fatally) if it is refused.
  void submit(const std::string& type, const std::string& text);

  dccl::Codec codec;
  queue::MemoryJournal journal;
  std::unique_ptr<queue::QueueManager> queues;
  v1::DriverConfig driver_config;
  std::unique_ptr<drivers::SimDriver> driver;
  std::unique_ptr<link::Driver> wrapper;  // setup.wrap_driver's, if any
  v1::MacConfig mac_config;
  std::unique_ptr<mac::Mac> mac;
  std::unique_ptr<link::LinkController> link;
};

}  // namespace acomms::testing
