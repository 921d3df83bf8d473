#pragma once
// Bringing a Micro-Modem up (spec §4.6), after opening the port and after
// every reboot.
//
// The problem: the driver depends on NVRAM settings a factory modem may not
// have (statistics, transmit reports, the revision at boot) and on SRC
// being this node's id (otherwise a local cycle becomes a poll, §10 quirk
// 11); NVRAM survives a reboot but the clock does not.
// The decision, in order:
//   1. listen for a `$CAREV` (MM1 or MM2, firmware revision) for `listen`;
//      a modem with REV=0 prints none, so then probe with `$CCCFQ,SRC`: no
//      answer is a start-up error;
//   2. write SRC = own id, then the settings the driver relies on
//      (driver_settings()), then the user's cfg list, one at a time, each
//      confirmed by its `$CACFG` echo (name and value);
//   3. set the clock, carrying the next UTC second, sent just after a
//      second boundary (goby3's way, §4.5): `$CCCLK` confirmed by `$CACLK`
//      on MM1, `$CCTMS` confirmed by `$CATMS` on MM2 (startup_clock.cpp);
//      a modem that printed no revision gets `$CCCLK`, then `$CCTMS` if
//      it refuses that.
// A setting the modem refuses (or never confirms) ends the start-up with an
// error naming it. Writing every value (rather than querying first) costs
// ~0.1 s per setting and keeps the sequence simple.
//
// Core thread only.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/scheduler.h"
#include "micromodem/command_queue.h"
#include "micromodem/nmea/config_sentences.h"

namespace acomms::drivers::micromodem {

using ::acomms::micromodem::ConfigParameter;
using ::acomms::micromodem::ModemGeneration;
using ::acomms::micromodem::Revision;

// The NVRAM values the driver depends on (spec §4.3), after SRC.
std::vector<ConfigParameter> driver_settings();

// "KEY,VALUE" from the config: three-letter names upper-cased (MM1 style),
// MM2 dotted names kept. Throws std::invalid_argument naming the entry.
ConfigParameter parse_cfg_entry(const std::string& entry);

// Does `echo` confirm writing `wanted`? Names compare without case, values
// as integers when both are (the modem echoes "1" for "01"), else as text.
bool confirms(const ConfigParameter& wanted, const ConfigParameter& echo);

class StartupSequence {
 public:
  struct Options {
    int own_id = 1;
    std::vector<ConfigParameter> user_cfg;
    Duration listen = std::chrono::seconds(2);
  };
  // `done("")` once ready, or done(why) once; never after the destructor.
  StartupSequence(CommandQueue& commands, core::Scheduler& scheduler, Options options,
                  std::function<void(const std::string& error)> done);
  ~StartupSequence();

  void begin();
  // Every $CAREV the driver reads (the AUV line ends the listening).
  void on_revision(const Revision& revision);

  bool finished() const { return finished_; }
  // From the AUV $CAREV, when one was seen.
  std::optional<ModemGeneration> generation() const { return generation_; }
  const std::string& revision() const { return revision_; }

 private:
  void probe();
  void write_settings();
  void write_next(size_t index);
  void set_clock();
  void set_clock_at_next_second(bool time_set, bool fall_back);
  void set_clock_mm2(const ::acomms::micromodem::ClockTime& carried);  // startup_clock.cpp
  void fail(const std::string& why);

  CommandQueue& commands_;
  core::Scheduler& scheduler_;
  Options options_;
  std::function<void(const std::string&)> done_;
  std::vector<ConfigParameter> settings_;
  core::Scheduler::TaskId timer_ = 0;
  bool listening_ = false;
  bool finished_ = false;
  std::optional<ModemGeneration> generation_;
  std::string revision_;
  // Command callbacks may outlive this object in the queue: they check it.
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace acomms::drivers::micromodem
