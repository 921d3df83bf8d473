#include "micromodem/micromodem_driver.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

#include "core/core_thread.h"
#include "link/transmission_rules.h"
#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/statistics_sentences.h"
#include "micromodem/poll_frames.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;
using nmea::Sentence;
using v1::ModemTransmission;

namespace {

constexpr std::chrono::seconds kKeepAlive{10};  // §4.5: a query every ~10 s
constexpr int kDeadAfter = 5;                   // unanswered commands in a row (§9)

Duration seconds_or(double seconds, Duration fallback) {
  if (seconds <= 0) return fallback;
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(seconds));
}

std::vector<ConfigParameter> user_cfg_of(const v1::DriverConfig& config) {
  std::vector<ConfigParameter> cfg;
  for (const std::string& entry : config.micromodem().cfg()) cfg.push_back(parse_cfg_entry(entry));
  return cfg;
}

double scale_of(const v1::DriverConfig& config) {
  double scale = config.micromodem().time_scale();
  if (scale < 0) throw std::invalid_argument("driver.micromodem.time_scale must be > 0 (0: real time)");
  return scale == 0 ? 1 : scale;
}

DriverSpecificExchange::Settings extra_settings(const v1::DriverConfig& config, int32_t id) {
  DriverSpecificExchange::Settings settings;
  settings.own_id = id;
  settings.time_scale = scale_of(config);
  double c = config.micromodem().sound_speed_mps();
  if (c < 0 || (c > 0 && (c < 1000 || c > 2000))) {
    throw std::invalid_argument("driver.micromodem.sound_speed_mps " + std::to_string(c) +
                                " is outside 1000..2000 m/s (0: 1500)");
  }
  if (c > 0) settings.sound_speed = c;
  if (config.micromodem().max_range_m() > 0) settings.max_range_m = config.micromodem().max_range_m();
  for (const ConfigParameter& p : user_cfg_of(config)) {
    if (p.name == "psk.packet.mod_hdr_version") settings.fdp_configured = p.value == "1";
  }
  for (uint32_t mm1 : config.micromodem().mm1_modems()) {
    if (mm1 < 1 || mm1 > static_cast<uint32_t>(nmea::kMaxAddress)) {
      throw std::invalid_argument("driver.micromodem.mm1_modems " + std::to_string(mm1) + " is not a modem id (1..127)");
    }
    settings.mm1_modems.push_back(static_cast<int32_t>(mm1));
  }
  return settings;
}

CycleTimeouts cycle_timeouts(const v1::DriverConfig& config) {
  CycleTimeouts t;
  if (config.micromodem().max_range_m() > 0) t.max_range_m = config.micromodem().max_range_m();
  t.time_scale = scale_of(config);
  return t;
}

}  // namespace

MicroModemDriver::MicroModemDriver(const v1::DriverConfig& config, core::Scheduler& scheduler,
                                   std::unique_ptr<ModemPort> port)
    : id_(link::own_modem_id(config)),
      label_("micromodem " + std::to_string(id_)),
      scheduler_(scheduler),
      port_(std::move(port)),
      user_cfg_(user_cfg_of(config)),
      time_scale_(scale_of(config)),
      max_range_m_(cycle_timeouts(config).max_range_m),
      sequence_({label_, id_, 0, 0, /*software_acks=*/config.micromodem().fdp_data()},
                {[this](const ModemTransmission& tx, bool report) { return send(tx, report); }}),
      bad_input_(label_),
      commands_(scheduler, [this](const Sentence& s) { write(s); },
                scaled(seconds_or(config.micromodem().command_timeout_s(), std::chrono::seconds(5)))),
      cycle_(scheduler, id_, cycle_timeouts(config),
             {[this](const Sentence& s) { write(s); },
              [this](const ModemTransmission& tx, bool ok, const std::string& error) {
                if (sequence_.running()) sequence_.report(tx, ok, error);
              },
              [this](const ModemTransmission& tx, Duration wait) { acks_.expect(tx, wait); }}),
      reception_([this] { return now_seconds(); },
                 [this](ModemTransmission rx) { sequence_.on_received(rx); }),
      acks_(scheduler, id_, [this](const ModemTransmission& ack) { sequence_.on_received(ack); }),
      extras_(scheduler, commands_, extra_settings(config, id_),
              {[this] { return generation_; },
               [this](const ModemTransmission& rx) {
                 if (sequence_.running() && sequence_.callbacks().on_receive) sequence_.callbacks().on_receive(rx);
               },
               [this] { return now_seconds(); }}),
      fdp_data_(config.micromodem().fdp_data()),
      mm1_modems_(extra_settings(config, id_).mm1_modems),
      fdp_(scheduler, commands_, id_, time_scale_,
           {[this](const ModemTransmission& tx, bool ok, const std::string& error) {
              if (sequence_.running()) sequence_.report(tx, ok, error);
            },
            [this](const ModemTransmission& rx) { sequence_.on_received(rx); },
            [this] { return now_seconds(); }}) {
  if (fdp_data_ && !extra_settings(config, id_).fdp_configured) {
    throw std::invalid_argument(
        "driver.micromodem.fdp_data needs cfg: \"psk.packet.mod_hdr_version,1\" (FDP packets; on every modem of "
        "the network)");
  }
  if (id_ > nmea::kMaxAddress) {
    throw std::invalid_argument("driver.modem_id " + std::to_string(id_) + " is not a Micro-Modem address (1..127)");
  }
  if (port_ == nullptr) throw std::invalid_argument("micromodem driver built without a port");
}

MicroModemDriver::~MicroModemDriver() { stop(); }

Duration MicroModemDriver::scaled(Duration d) const {
  return std::chrono::duration_cast<Duration>(d / time_scale_);
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
  if (fdp_data_ && transmission.type() == ModemTransmission::DATA && transmission.src() == id_) {
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
  if (tx.type() != ModemTransmission::ACK && !(tx.type() == ModemTransmission::DATA && tx.src() == id_)) {
    return "driver.micromodem.fdp_data: only this node's DATA and ACKs go out as FDP (asked for type " +
           std::to_string(tx.type()) + " from " + std::to_string(tx.src()) + ")";
  }
  if (std::find(mm1_modems_.begin(), mm1_modems_.end(), tx.dest()) != mm1_modems_.end()) {
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
  if (fdp_data_) return send_fdp(tx, report);
  if (tx.type() != ModemTransmission::DATA) {
    return "the micromodem driver sends DATA and polls only (asked for type " + std::to_string(tx.type()) + ")";
  }
  if (!ready_) return "the modem is not ready (start-up in progress)";
  if (!commands_.idle()) return "busy: a command to the modem is waiting for its reply";
  if (!extras_.idle()) return "busy: a driver-specific exchange (ping, LBL, ...) is in progress";
  if (tx.src() == id_ || answering_poll_) return cycle_.start(tx, answering_poll_);
  // A third-party cycle: Nframes sized for what is left of the slot.
  v1::ModemTransmission poll = tx;
  poll.set_max_num_frames(poll_frames(*this, tx, scheduler_.clock().now(), max_range_m_));
  if (poll.max_num_frames() == 0) {
    return "the slot has no room left for node " + std::to_string(tx.src()) + "'s answer at rate " +
           std::to_string(tx.rate());
  }
  return cycle_.start(poll, false);
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
  options.own_id = id_;
  options.user_cfg = user_cfg_;
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
  spdlog::info("{}: {} ready on {} (SRC {})", label_, kind, port_->name(), id_);
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

template <typename T>
bool MicroModemDriver::parsed(const nmea::Result<T>& result, const Sentence& sentence) {
  if (result) return true;
  bad_input_.note("malformed " + sentence.address(), result.error().text, scheduler_.clock().now());
  return false;
}

void MicroModemDriver::dispatch(const Sentence& s) {
  if (dispatch_driver_specific(s)) return;
  if (s.talker == "CA") {
    const std::string& t = s.type;
    if (t == "REV") return on_revision(s);
    if (t == "CFG" || t == "CLK" || t == "TMS") {
      commands_.on_sentence(s);  // else a line of a dump, or a late echo
      return;
    }
    if (t == "CYC") return on_cycle(s);
    if (t == "ERR") return on_error(s);
    if (t == "DRQ") {
      auto r = nmea::parse_data_request(s);
      if (parsed(r, s)) cycle_.on_data_request(*r);
      return;
    }
    if (t == "TXD") {
      auto r = nmea::parse_transmit_data_accepted(s);
      parsed(r, s);
      return;
    }
    if (t == "TXP") {
      auto r = nmea::parse_transmit_started(s);
      if (parsed(r, s)) cycle_.on_transmit_started(*r);
      return;
    }
    if (t == "TXF") {
      auto r = nmea::parse_transmit_finished(s);
      if (parsed(r, s)) cycle_.on_transmit_finished(*r);
      return;
    }
    if (t == "XST") {
      auto r = nmea::parse_transmit_statistics(s);
      if (parsed(r, s)) cycle_.on_transmit_statistics(*r);
      return;
    }
    if (t == "RXP") {
      auto r = nmea::parse_receive_started(s);
      if (parsed(r, s)) reception_.on_receive_started();
      return;
    }
    if (t == "RXD") {
      auto r = nmea::parse_received_data(s);
      if (parsed(r, s)) reception_.on_data(*r);
      return;
    }
    if (t == "MSG") {
      auto r = nmea::parse_transaction_message(s);
      if (parsed(r, s)) {
        reception_.on_message(*r);
        cycle_.on_message(*r);
      }
      return;
    }
    if (t == "CST") {
      auto r = nmea::parse_receive_statistics(s);
      if (parsed(r, s)) reception_.on_statistics(*r);
      acks_.on_statistics();
      return;
    }
    if (t == "ACK") {
      auto r = nmea::parse_acknowledgement(s);
      if (parsed(r, s)) acks_.on_ack(*r);
      return;
    }
    // Known and not needed by a data driver (clock and device queries,
    // ping/LBL/mini-packet echoes, MM2 clock reports).
    static const char* const kIgnored[] = {"TMQ", "TMG", "ALQ", "CLQ", "MPC", "MPA", "MPR", "MUC", "MUA",
                                           "MUR", "MEC", "MEA", "MER", "MSC", "MSA", "MSR", "TDP", "RDP", "CDR",
                                           "DQF", "DOP", "MFD", "SHF", "SNR", "TOA", "RXA", "TXA"};
    for (const char* ignored : kIgnored) {
      if (t == ignored) return;
    }
  } else if (s.talker == "SN" || s.talker == "GP") {
    return;  // navigation and forwarded GPS: not used by this driver
  }
  bad_input_.note("unknown sentence", "$" + s.address() + " ignored", scheduler_.clock().now());
}

void MicroModemDriver::on_revision(const Sentence& s) {
  auto revision = nmea::parse_revision(s);
  if (!parsed(revision, s)) return;
  if (revision->is_boot()) return on_reboot();
  if (revision->identifier == "AUV") {
    auto generation = nmea::modem_generation(revision->revision);
    if (generation) generation_ = *generation;
    revision_ = revision->revision;
    // Before the start-up writes the FDP header setting an MM1 would refuse.
    if (refuse_fdp_on_mm1()) return;
  }
  if (startup_) startup_->on_revision(*revision);
}

bool MicroModemDriver::refuse_fdp_on_mm1() {
  if (!fdp_data_ || generation_ != ModemGeneration::kMM1) return false;
  startup_.reset();
  commands_.clear("driver.micromodem.fdp_data on a Micro-Modem 1");
  fatal_ = "driver.micromodem.fdp_data needs a Micro-Modem 2: this modem is " + modem() +
           " (FDP, $CCTDP/$CARDP, is MM2 only)";
  spdlog::error("{}: {}", label_, fatal_);
  return true;
}

void MicroModemDriver::on_cycle(const Sentence& s) {
  auto cycle = nmea::parse_cycle(s);
  if (!parsed(cycle, s)) return;
  if (cycle_.on_cycle(*cycle)) return;  // the echo of our $CCCYC
  reception_.on_cycle(*cycle);
  // ADR1 = our SRC from the water: another node polls us (§8.2).
  if (cycle->source == id_ && ready_ && cycle_.idle()) answer_poll(*cycle);
}

void MicroModemDriver::answer_poll(const nmea::Cycle& cycle) {
  // A frameless DATA under our own id is how driver_sequence recognises a
  // poll for us; it asks the queues and calls send(), which then starts an
  // exchange without a $CCCYC of ours (answering_poll_).
  ModemTransmission poll;
  poll.set_type(ModemTransmission::DATA);
  poll.set_src(id_);
  poll.set_dest(cycle.destination);
  poll.set_rate(cycle.rate);
  poll.set_ack_requested(cycle.ack);
  poll.set_max_num_frames(polled_frames(cycle.rate, cycle.frames));  // Nframes: what the master asked for
  poll.set_time(now_seconds());
  answering_poll_ = true;
  sequence_.on_received(poll);
  answering_poll_ = false;
}

void MicroModemDriver::on_error(const Sentence& s) {
  auto error = nmea::parse_modem_error(s);
  if (!parsed(error, s)) return;
  bad_input_.note("modem error", "$CAERR " + error->module + " " + error->number + " " + error->message,
                  scheduler_.clock().now());
  if (commands_.on_error(*error)) return;
  cycle_.on_error(*error);
}

std::chrono::nanoseconds MicroModemDriver::packet_air_time(int32_t rate, uint32_t num_frames) const {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(link::Driver::packet_air_time(rate, num_frames) /
                                                              time_scale_);
}

std::chrono::nanoseconds MicroModemDriver::ack_time(int32_t rate) const {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(link::Driver::ack_time(rate) / time_scale_);
}

link::DriverCounters MicroModemDriver::counters() const {
  link::DriverCounters counters;
  counters.bad_input = bad_input_.counts();
  return counters;
}

std::string MicroModemDriver::modem() const {
  if (!generation_) return "";
  return (*generation_ == ModemGeneration::kMM1 ? "MM1 " : "MM2 ") + revision_;
}

double MicroModemDriver::sound_speed() const { return link::Driver::sound_speed() * time_scale_; }

}  // namespace acomms::drivers::micromodem
