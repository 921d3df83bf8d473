#pragma once
// Issue 30's network with real acommsd processes: a shore, a gateway buoy
// and two vehicles, one of which only the other hears.
//
//   shore (1) iridium_shore ─ FakeDirectIpGateway ─ fake 9603 ─ iridium  buoy (2)
//   buoy (2)  sim "acoustic" ─ vehicle A (3) ─ sim "acoustic" ─ vehicle B (4)
//
// The problem. The gateway must be shown between real processes, with the
// satellite hop on the Iridium fakes (both drivers: iridium_shore on the
// shore, iridium on the buoy) and the buoy killed while it holds messages;
// an in-process network (tests/system/gateway_network_test.cpp) cannot
// SIGKILL a node or run two different drivers.
//
// The decisions.
//  - Who hears whom is the sim driver's `peers` list (each node sends every
//    packet to its peers only): the buoy's peer is A, A's are the buoy and
//    B, B's is A. B and the buoy never hear each other, so B is reachable
//    only through A, with no physics to tune. All sit within 100 m
//    (max_range_m 100): three 2.5 s slots at rate 5 (one frame, its ACK and
//    the travel fit) make a 7.5 s cycle.
//  - Routes. Static only where nothing can be learned before it is needed:
//    the shore's plan (vehicles 3-4 through the buoy, by satellite), the
//    buoy's and A's way to the shore, B's way out through A. Learned: the
//    buoy hears A (and the shore on each MT), learns B through A from B's
//    relayed statuses; the shore learns both vehicles through the buoy.
//  - A loop for node 20: the buoy routes it to A and A back to the buoy; the
//    shore's hop_limit 4 ends it at A (hops 2 at the buoy, 3 at A, 4 at the
//    buoy, dropped at A), which is never killed, so its counter survives.
//  - The buoy loads examples/messages.proto only; the shore and the
//    vehicles also load the survey plan type (survey_plan_proto()), which
//    the buoy therefore forwards without ever having loaded it.
//  - The Iridium fakes live in this process, so they outlive the buoy's
//    deaths like a real gateway and modem: the modem keeps its MT buffer
//    and MOMSN, the gateway its MT queue.
//
// Thread-safety: one test thread drives a fleet; socket() and the API
// calls through api() may be used from other threads too (gRPC stubs).

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "child_process.h"
#include "daemon_harness.h"
#include "fake_directip_gateway.h"
#include "tcp_modem_host.h"

namespace acomms::testing {

inline constexpr int kShore = 1;
inline constexpr int kBuoy = 2;
inline constexpr int kVehicleA = 3;
inline constexpr int kVehicleB = 4;
inline constexpr int kNowhere = 20;  // the loop's destination: no node has it
inline constexpr double kAcousticSlotS = 2.5;
inline constexpr int kShoreHopLimit = 4;

class GatewayFleet {
 public:
  // A fresh directory under /tmp, the fakes started (MO pushes to a port
  // the shore will listen on).
  GatewayFleet();
  ~GatewayFleet();  // SIGTERMs what runs; removes the directory unless the test failed

  static std::string name(int node);  // "shore", "buoy", "vehicle_a", "vehicle_b"
  std::string socket(int node) const;
  const std::filesystem::path& dir() const { return dir_; }
  std::string survey_plan_proto() const { return (dir_ / "survey_plan.proto").string(); }

  // Writes every node's config and starts the four daemons (each waits
  // until it serves; a fatal failure with its log if one does not).
  void start_all();
  void start(int node);
  // SIGKILL, and the death checked to be by SIGKILL.
  void kill(int node);
  ChildProcess& daemon(int node) { return *daemons_.at(node); }
  // Every start's stderr of `node`, oldest first.
  std::string logs(int node) const;
  // Every node's logs and the fake modem's transcript tail, for failures.
  std::string all_logs() const;
  void stop_all();

  fake_iridium::FakeDirectIpGateway& directip() { return directip_; }
  fake_iridium::TcpModemHost& modem() { return modem_; }

 private:
  std::string config_text(int node) const;
  std::string acoustic_link(int node) const;

  std::filesystem::path dir_;
  int mo_port_;
  std::map<int, int> sim_port_;
  fake_iridium::FakeDirectIpGateway directip_;
  fake_iridium::TcpModemHost modem_;
  std::map<int, std::unique_ptr<ChildProcess>> daemons_;
  std::map<int, int> starts_;
};

}  // namespace acomms::testing
