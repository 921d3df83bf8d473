#pragma once
// Real acommsd processes on fake Micro-Modems: one fake_micromodem process
// (its modems share one water, each on a TCP port like a serial-to-TCP
// gateway) and one daemon per modem, with the fake's fault console on a
// FIFO so a test can hurt a modem or its line while the daemons run.
//
// Everything runs faster than real time by `time_scale` (the fake's
// --time-scale and driver.micromodem.time_scale), except the MAC's slots,
// which are real seconds: the slot budget sees the sped-up air times.
//
// A test waits for what it needs (a status, a message) and never sleeps
// to let a process get somewhere (daemon_harness.h).

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "acomms/v1/acomms.grpc.pb.h"
#include "daemon_harness.h"

namespace acomms::testing {

class MicroModemNetwork {
 public:
  struct Modem {
    int id;
    std::string spec;  // fake_micromodem --modem: "1,mm2,300,0,0"
  };
  // Starts the fake (not the daemons) in a fresh directory under /tmp named
  // after `name`. Check ok() (and fake_output() when it is not).
  // `fake_args`: more options for the fake (e.g. {"--frame-errors", "0.3"}).
  MicroModemNetwork(const std::string& name, std::vector<Modem> modems, double time_scale,
                    std::vector<std::string> fake_args = {});
  ~MicroModemNetwork();  // SIGTERMs what runs (expecting exit 0 from daemons) and removes the directory

  bool ok() const { return ok_; }
  std::string fake_output() const;
  const std::filesystem::path& dir() const { return dir_; }

  // Writes node `id`'s config: its modem on the fake's port, example
  // messages (example.Command queued with roles), `mac` inside mac { },
  // `micromodem` appended to its driver's micromodem { } settings.
  // `extra` is appended to the config (a gram { } block, say).
  void write_config(int id, const std::string& mac, const std::string& micromodem = "", const std::string& extra = "");
  // Starts node `id`'s daemon and waits until it serves (false if not).
  bool start(int id);
  ChildProcess& daemon(int id) { return *daemons_.at(id); }
  std::string socket(int id) const;
  std::string daemon_log(int id) const;

  // One fault console command ("2 reset", "2 unplug", ...); waits for the
  // fake's answer and returns it ("ok", or what was wrong).
  std::string fault(const std::string& command);

  // gRPC helpers on node `id`. submit_command() returns the Submit status.
  grpc::Status submit_command(int id, int dest, int seq, v1::SubmitResponse* response = nullptr);
  int queued(int id);
  v1::LinkStatusResponse link_status(int id);
  // `acommsctl link raw --no-follow` on node `id` (its whole raw log).
  RunResult raw_log(int id);

 private:
  std::filesystem::path dir_;
  std::vector<Modem> modems_;
  double time_scale_;
  bool ok_ = false;
  int console_ = -1;        // the fake's stdin (a FIFO), written by fault()
  size_t answers_seen_ = 0;  // console answers already read from the fake's stdout
  std::unique_ptr<ChildProcess> fake_;
  std::map<int, std::string> address_;  // modem id → "127.0.0.1:PORT"
  std::map<int, std::unique_ptr<ChildProcess>> daemons_;
};

}  // namespace acomms::testing
