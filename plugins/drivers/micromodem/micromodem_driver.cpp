// The driver's lifecycle (micromodem_driver.h): built from its settings,
// started by opening the port, brought up by the start-up sequence (again
// after every reboot), kept alive by a query when the line is quiet, and
// stopped with every exchange in flight failed to its owner; and its
// sending, which starts the one exchange the modem can run at a time.
// Received sentences are routed in micromodem_sentence_routes.cpp.
#include "micromodem/micromodem_driver.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

#include "core/core_thread.h"
#include "micromodem/nmea/config_sentences.h"
#include "micromodem/poll_frames.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;
using nmea::Sentence;
using v1::ModemTransmission;

namespace {

constexpr std::chrono::seconds kKeepAlive{10};  // §4.5: a query every ~10 s
constexpr int kDeadAfter = 5;                   // unanswered commands in a row (§9)

}  // namespace

MicroModemDriver::MicroModemDriver(const v1::DriverConfig& config, core::Scheduler& scheduler,
                                   std::unique_ptr<ModemPort> port)
    : settings_(read_micromodem_settings(config)),
      label_("micromodem " + std::to_string(settings_.id)),
      scheduler_(scheduler),
      port_(std::move(port)),
      sequence_({label_, settings_.id, 0, 0, /*software_acks=*/settings_.fdp_data},
                {[this](const ModemTransmission& tx, bool report) { return send(tx, report); }}),
      bad_input_(label_),
      commands_(scheduler, [this](const Sentence& s) { write(s); }, scaled(settings_.command_timeout)),
      cycle_(scheduler, settings_.id, settings_.cycle,
             {[this](const Sentence& s) { write(s); },
              [this](const ModemTransmission& tx, bool ok, const std::string& error) {
                if (sequence_.running()) sequence_.report(tx, ok, error);
              },
              [this](const ModemTransmission& tx, Duration wait) { acks_.expect(tx, wait); }}),
      reception_(settings_.id, [this] { return now_seconds(); },
                 [this](ModemTransmission rx) { sequence_.on_received(rx); }),
      acks_(scheduler, settings_.id, [this](const ModemTransmission& ack) { sequence_.on_received(ack); }),
      extras_(scheduler, commands_, settings_.exchange,
              {[this] { return generation_; },
               [this](const ModemTransmission& rx) {
                 if (sequence_.running() && sequence_.callbacks().on_receive) sequence_.callbacks().on_receive(rx);
               },
               [this] { return now_seconds(); }}),
      fdp_(scheduler, commands_, settings_.id, settings_.time_scale,
           {[this](const ModemTransmission& tx, bool ok, const std::string& error) {
              if (sequence_.running()) sequence_.report(tx, ok, error);
            },
            [this](const ModemTransmission& rx) { sequence_.on_received(rx); },
            [this] { return now_seconds(); }}) {
  if (port_ == nullptr) throw std::invalid_argument("micromodem driver built without a port");
  reception_.set_on_failed([this](const ModemTransmission& lost) {
    if (sequence_.running() && sequence_.callbacks().on_reception_failed) sequence_.callbacks().on_reception_failed(lost);
  });
}

MicroModemDriver::~MicroModemDriver() { stop(); }

Duration MicroModemDriver::scaled(Duration d) const {
  return std::chrono::duration_cast<Duration>(d / settings_.time_scale);
}

double MicroModemDriver::now_seconds() const {
  return scheduler_.clock().now_seconds();
}

void MicroModemDriver::start(link::DriverCallbacks callbacks) {
  ACOMMS_ASSERT_CORE_THREAD();
  stop();
  sequence_.start(std::move(callbacks));
  fatal_.clear();
  last_line_ = scheduler_.clock().now();
  port_->open([this](std::string_view bytes) { on_bytes(bytes); },
              [this](link::TransportState state, const std::string& detail) { on_port_state(state, detail); });
  spdlog::info("{}: opening {}", label_, port_->name());
}

void MicroModemDriver::stop() {
  port_->close();
  startup_.reset();
  ready_ = false;
  // Failures of what was in flight still reach the sequence's owner.
  cycle_.abort("the driver stopped");
  extras_.abort("the driver stopped");
  fdp_.abort("the driver stopped");
  commands_.clear("the driver stopped");
  acks_.reset();
  reception_.reset();
  framer_.reset();
  sequence_.stop();
}

void MicroModemDriver::do_work() {
  ACOMMS_ASSERT_CORE_THREAD();
  sequence_.check_running();
  if (!fatal_.empty()) throw link::DriverError(label_ + ": " + fatal_);
  if (commands_.consecutive_failures() >= kDeadAfter) {
    bad_input_.note("silent modem", std::to_string(kDeadAfter) + " commands in a row unanswered",
                    scheduler_.clock().now());
    throw link::DriverError(label_ + ": the modem on " + port_->name() + " is silent: " +
                            std::to_string(kDeadAfter) + " commands in a row were not answered");
  }
  keep_alive();
}

void MicroModemDriver::keep_alive() {
  if (!ready_ || !cycle_.idle() || !commands_.idle() || !extras_.idle() || !fdp_.idle()) return;
  if (scheduler_.clock().now() - last_line_ < scaled(kKeepAlive)) return;
  last_line_ = scheduler_.clock().now();  // one probe per quiet period
  commands_.push({to_sentence(nmea::ConfigQuery{"SRC"}),
                  [](const Sentence& s) { return s.is("CACFG") && s.field(1) == "SRC"; },
                  [this](bool ok, const Sentence*, const std::string& why) {
                    // (Not when the queue was cleared: a reboot, stop().)
                    if (!ok && why.starts_with("no reply")) {
                      bad_input_.note("silent modem", "keep-alive: " + why, scheduler_.clock().now());
                    }
                  },
                  1});
}

void MicroModemDriver::initiate_transmission(const ModemTransmission& transmission) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (settings_.fdp_data && transmission.type() == ModemTransmission::DATA && transmission.src() == settings_.id) {
    // Our DATA as FDP: as many of the rate's frames as one packet holds.
    sequence_.check_running();
    uint32_t frames = FdpDataLink::max_num_frames(transmission.rate());
    if (frames == 0) {
      return sequence_.report(transmission, false,
                              "driver.micromodem.fdp_data: rate " + std::to_string(transmission.rate()) +
                                  " is not an FDP rate (1, 3 or 5)");
    }
    ModemTransmission fdp = transmission;
    if (fdp.max_num_frames() == 0 || fdp.max_num_frames() > frames) fdp.set_max_num_frames(frames);
    return sequence_.transmit(fdp);
  }
  sequence_.transmit(transmission);
}

std::string MicroModemDriver::send_fdp(const ModemTransmission& tx, bool report) {
  if (tx.type() != ModemTransmission::ACK && !(tx.type() == ModemTransmission::DATA && tx.src() == settings_.id)) {
    return "driver.micromodem.fdp_data: only this node's DATA and ACKs go out as FDP (asked for type " +
           std::to_string(tx.type()) + " from " + std::to_string(tx.src()) + ")";
  }
  const std::vector<int32_t>& mm1_modems = settings_.exchange.mm1_modems;
  if (std::find(mm1_modems.begin(), mm1_modems.end(), tx.dest()) != mm1_modems.end()) {
    return "cannot send FDP data to modem " + std::to_string(tx.dest()) +
           ": it is a Micro-Modem 1 (driver.micromodem.mm1_modems), which cannot decode the flexible data protocol";
  }
  if (!ready_) return "the modem is not ready (start-up in progress)";
  if (tx.type() == ModemTransmission::ACK) {
    // The command queue serializes it behind a keep-alive; the sequence
    // does not log an ACK's failure, so it is logged here.
    std::string why = fdp_.send(tx, false);
    if (!why.empty()) spdlog::warn("{}: FDP acknowledgement to {} not sent: {}", label_, tx.dest(), why);
    return why;
  }
  if (!commands_.idle()) return "busy: a command to the modem is waiting for its reply";
  if (!extras_.idle()) return "busy: a driver-specific exchange (ping, LBL, ...) is in progress";
  return fdp_.send(tx, report);
}

std::string MicroModemDriver::send(const ModemTransmission& tx, bool report) {
  if (settings_.fdp_data) return send_fdp(tx, report);
  if (tx.type() != ModemTransmission::DATA) {
    return "the micromodem driver sends DATA and polls only (asked for type " + std::to_string(tx.type()) + ")";
  }
  if (!ready_) return "the modem is not ready (start-up in progress)";
  if (!commands_.idle()) return "busy: a command to the modem is waiting for its reply";
  if (!extras_.idle()) return "busy: a driver-specific exchange (ping, LBL, ...) is in progress";
  if (tx.src() == settings_.id || answering_poll_) return cycle_.start(tx, answering_poll_);
  // A third-party cycle: Nframes sized for what is left of the slot.
  v1::ModemTransmission poll = tx;
  poll.set_max_num_frames(poll_frames(*this, tx, scheduler_.clock().now(), settings_.cycle.max_range_m));
  if (poll.max_num_frames() == 0) {
    return "the slot has no room left for node " + std::to_string(tx.src()) + "'s answer at rate " +
           std::to_string(tx.rate());
  }
  std::string refused = cycle_.start(poll, false);
  // Its answer is awaited: a timeout is a packet lost (reception.h).
  if (refused.empty()) reception_.expect(poll.src(), poll.dest() >= 0 ? poll.dest() : settings_.id, poll.rate());
  return refused;
}

void MicroModemDriver::on_port_state(link::TransportState state, const std::string& detail) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (state == link::TransportState::kOpen) {
    framer_.reset();  // stale bytes from before (§10 quirk 20)
    spdlog::info("{}: {} open; starting the modem", label_, detail);
    begin_startup();
  } else if (state == link::TransportState::kWaiting) {
    // The transport would reconnect, but the modem's state is unknown
    // then: a restart of the whole driver (with backoff) is clearer.
    ready_ = false;
    cycle_.abort("the port to the modem was lost");
    fatal_ = "the port was lost: " + detail;
  }
}

void MicroModemDriver::begin_startup() {
  ready_ = false;
  StartupSequence::Options options;
  options.own_id = settings_.id;
  options.user_cfg = settings_.user_cfg;
  options.listen = scaled(std::chrono::seconds(2));
  startup_ = std::make_unique<StartupSequence>(commands_, scheduler_, options,
                                               [this](const std::string& error) { on_startup_done(error); });
  startup_->begin();
}

void MicroModemDriver::on_startup_done(const std::string& error) {
  if (!error.empty()) {
    fatal_ = error;
    spdlog::error("{}: {}", label_, error);
    return;
  }
  if (startup_->generation()) generation_ = startup_->generation();
  if (refuse_fdp_on_mm1()) return;
  ready_ = true;
  if (!startup_->revision().empty()) revision_ = startup_->revision();
  std::string kind = modem().empty() ? "Micro-Modem (revision not seen yet)" : modem();
  spdlog::info("{}: {} ready on {} (SRC {})", label_, kind, port_->name(), settings_.id);
}

void MicroModemDriver::on_reboot() {
  if (ready_) {
    ++reboots_;
    spdlog::warn("{}: the modem rebooted ($CAREV INIT): failing the exchange in progress, applying the settings again",
                 label_);
  } else {
    spdlog::info("{}: the modem is booting ($CAREV INIT)", label_);
  }
  // The start-up first: its pending commands then fail without reaching it.
  startup_.reset();
  commands_.clear("the modem rebooted");
  cycle_.abort("the modem rebooted ($CAREV INIT) during the exchange");
  extras_.abort("the modem rebooted ($CAREV INIT) during the exchange");
  fdp_.abort("the modem rebooted ($CAREV INIT) during the FDP packet");
  acks_.reset();
  reception_.reset();
  begin_startup();  // listens for the AUV line first: the modem is booting (§4.1)
}

bool MicroModemDriver::refuse_fdp_on_mm1() {
  if (!settings_.fdp_data || generation_ != ModemGeneration::kMM1) return false;
  startup_.reset();
  commands_.clear("driver.micromodem.fdp_data on a Micro-Modem 1");
  fatal_ = "driver.micromodem.fdp_data needs a Micro-Modem 2: this modem is " + modem() +
           " (FDP, $CCTDP/$CARDP, is MM2 only)";
  spdlog::error("{}: {}", label_, fatal_);
  return true;
}

void MicroModemDriver::write(const Sentence& sentence) {
  std::string line = nmea::serialize(sentence);
  if (sequence_.callbacks().on_raw) sequence_.callbacks().on_raw(line, true);
  line += nmea::kLineEnd;
  if (!port_->write(line)) spdlog::debug("{}: port not open, dropped {}", label_, line.substr(0, line.size() - 2));
}

void MicroModemDriver::on_bytes(std::string_view bytes) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!sequence_.running()) return;
  std::vector<std::string> lines = framer_.push(bytes);
  const auto& now_counters = framer_.counters();
  auto now = scheduler_.clock().now();
  bad_input_.note("noise", "bytes outside any sentence", now, now_counters.noise_bytes - framer_seen_.noise_bytes);
  bad_input_.note("truncated line", "a sentence cut short by a new '$'", now,
                  now_counters.truncated_lines - framer_seen_.truncated_lines);
  bad_input_.note("over-long line", "longer than " + std::to_string(nmea::kMaxLineLength) + " characters", now,
                  now_counters.overlong_lines - framer_seen_.overlong_lines);
  framer_seen_ = now_counters;
  for (const std::string& line : lines) {
    if (!sequence_.running()) return;  // a callback stopped the driver
    on_line(line);
  }
}

void MicroModemDriver::on_line(const std::string& line) {
  last_line_ = scheduler_.clock().now();
  if (sequence_.callbacks().on_raw) sequence_.callbacks().on_raw(line, false);
  auto sentence = nmea::parse_sentence(line);
  if (!sentence) {
    bad_input_.note(std::string(nmea::to_string(sentence.error().kind)), sentence.error().text, last_line_);
    return;
  }
  dispatch(*sentence);
}

std::chrono::nanoseconds MicroModemDriver::packet_air_time(int32_t rate, uint32_t num_frames) const {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(link::Driver::packet_air_time(rate, num_frames) /
                                                              settings_.time_scale);
}

std::chrono::nanoseconds MicroModemDriver::ack_time(int32_t rate) const {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(link::Driver::ack_time(rate) / settings_.time_scale);
}

link::DriverCounters MicroModemDriver::counters() const {
  link::DriverCounters counters;
  counters.bad_input = bad_input_.counts();
  // Damaged packets the calibration cannot use: nothing named their sender
  // (reception.h). Shown with the rest by `acommsctl link status`.
  if (const uint64_t unattributed = reception_.counters().unattributed) {
    counters.bad_input["damaged packet, sender unknown"] = unattributed;
  }
  return counters;
}

std::string MicroModemDriver::modem() const {
  if (!generation_) return "";
  return (*generation_ == ModemGeneration::kMM1 ? "MM1 " : "MM2 ") + revision_;
}

double MicroModemDriver::sound_speed() const { return link::Driver::sound_speed() * settings_.time_scale; }

}  // namespace acomms::drivers::micromodem
