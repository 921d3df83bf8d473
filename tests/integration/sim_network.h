#pragma once
// Two real acommsd processes, the vehicle (node 1) and the topside (node 2),
// on the loopback sim channel: each node's sim driver listens on a free UDP
// port of its own and sends to the other's. The MAC is fixed TDMA, one slot
// per node at rate 5, with a 400 m range guard: the tests keep the nodes
// within 300 m, and the default 2000 m guard would leave a slot of a few
// seconds no room for a packet and its ACK (link/slot_budget.h).
//
// The system tests differ only in what SimNetwork::Node says; they drive the
// daemons through the gRPC API on socket(id) and kill them with daemon(id).
// A test waits for what it needs and never sleeps to let a process get
// somewhere (daemon_harness.h).

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "daemon_harness.h"

namespace acomms::testing {

class SimNetwork {
 public:
  // What a test chooses in a node's config.
  struct Node {
    std::string sim;               // sim { } settings besides listen and peers: "position { x: 300 }"
    std::string rest;              // config after mac { }: queue { }, telemetry { }
    bool example_messages = true;  // dccl { proto_files: examples/messages.proto }
  };

  // A fresh directory under /tmp named after `name`, and the nodes' ports.
  SimNetwork(const std::string& name, double slot_seconds);
  ~SimNetwork();  // removes the directory, unless the test failed: its logs are there

  static std::string name(int id) { return id == 1 ? "vehicle" : "topside"; }
  const std::filesystem::path& dir() const { return dir_; }
  std::string socket(int id) const;

  void write_config(int id, const Node& node);
  // One queue { type { } } entry for an example message (their src, dest
  // and time fields are its roles), `policy` inside its policy { }.
  static std::string queue_type(const std::string& type, const std::string& policy);
  // Starts node `id`'s daemon (a new log per start) and waits until it
  // serves; a fatal test failure, with its log, if it does not.
  void start(int id);
  ChildProcess& daemon(int id) { return *daemons_.at(id); }
  // SIGTERMs every daemon still running (SIGCONT first: a test may have
  // stopped one) and expects each to exit 0. For the test's TearDown.
  void stop();

 private:
  std::filesystem::path dir_;
  double slot_seconds_;
  std::map<int, int> port_;
  std::map<int, std::unique_ptr<ChildProcess>> daemons_;
  int starts_ = 0;
};

}  // namespace acomms::testing
