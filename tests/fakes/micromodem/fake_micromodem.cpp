// The fake modem's host side: output, start-up, configuration, clock and
// command dispatch. Cycles are in fake_micromodem_cycle.cpp, reception in
// fake_micromodem_reception.cpp.

#include "fake_micromodem.h"
#include "fake_micromodem_state.h"

#include <cstdio>
#include <ctime>

#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/receive_sentences.h"

namespace acomms::fake_micromodem {

using namespace micromodem;

// Error numbers are not public (§13): these are the fake's own.
namespace error_number {
constexpr const char* kUnparseable = "1";
constexpr const char* kBadChecksum = "2";
constexpr const char* kUnknownCommand = "3";
constexpr const char* kBadValue = "4";
}  // namespace error_number

FakeMicroModem::FakeMicroModem(Water& water, FakeModemConfig config)
    : water_(water),
      config_(config),
      nvram_(config.generation, config.address),
      faults_(config.seed + 1000),
      random_(config.seed) {
  water_.join(this);
}

FakeMicroModem::~FakeMicroModem() { water_.leave(this); }

std::string FakeMicroModem::revision() const {
  // The recommended MM1 build (SIG v3.24) and the MM2 build of the public
  // transcripts (§4.1).
  return config_.generation == Generation::kMM1 ? "0.94.0.04" : "2.0.27087";
}

void FakeMicroModem::later(Duration delay, std::function<void()> task) {
  std::weak_ptr<uint64_t> life = life_;
  uint64_t this_life = *life_;
  water_.scheduler().after(delay, [life, this_life, task = std::move(task)] {
    auto alive = life.lock();
    if (alive && *alive == this_life) task();
  });
}

void FakeMicroModem::write_raw(std::string_view bytes) {
  if (output_ && !faults_.silent()) output_(bytes);
}

void FakeMicroModem::emit(const Sentence& sentence) {
  if (!output_ || faults_.silent()) return;
  std::string line = faults_.apply(serialize(sentence) + std::string(kLineEnd));
  output_(line);
}

void FakeMicroModem::report_error(const std::string& module, const std::string& number,
                                  const std::string& message) {
  emit(to_sentence(ModemError{modem_time_hhmmss(), module, number, message}));
}

void FakeMicroModem::power_on() {
  booted_ = true;
  boot_time_ = water_.scheduler().clock().now();
  clock_offset_.reset();
  print_revision(true);
  later(config_.timing.boot, [this] { print_revision(false); });
  schedule_revision();
}

void FakeMicroModem::reboot() {
  ++*life_;  // abandons every pending task: cycles, receptions, replies
  exchange_.reset();
  reception_.reset();
  awaited_poll_.reset();
  buffered_frames_.clear();
  transmitting_until_ = water_.scheduler().clock().now();
  host_framer_.reset();
  power_on();
}

void FakeMicroModem::print_revision(bool boot) {
  std::string time = modem_time_hhmmss();
  if (boot) {
    emit(to_sentence(Revision{time, "INIT", revision()}));
    return;
  }
  emit(to_sentence(Revision{time, "AUV", revision()}));
  if (config_.generation == Generation::kMM2) emit(to_sentence(Revision{time, "COPROC", "0.20.0.56"}));
}

void FakeMicroModem::schedule_revision() {
  if (config_.timing.revision_period <= Duration::zero()) return;
  later(config_.timing.revision_period, [this] {
    if (nvram_.flag("REV")) print_revision(false);
    schedule_revision();
  });
}

Duration FakeMicroModem::modem_time_since_epoch() const {
  auto now = water_.scheduler().clock().now();
  // An unset clock counts from the Unix epoch at boot (the fake's choice).
  if (!clock_offset_) return now - boot_time_;
  return now.time_since_epoch() + *clock_offset_;
}

namespace {

std::tm utc(Duration since_epoch) {
  std::time_t seconds = std::chrono::duration_cast<std::chrono::seconds>(since_epoch).count();
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  return tm;
}

}  // namespace

std::string FakeMicroModem::modem_time_hhmmss() const {
  std::tm tm = utc(modem_time_since_epoch());
  char text[16];
  std::snprintf(text, sizeof text, "%02d%02d%02d", tm.tm_hour, tm.tm_min, tm.tm_sec);
  return text;
}

std::string FakeMicroModem::modem_date_time(int decimals) const {
  Duration since = modem_time_since_epoch();
  std::tm tm = utc(since);
  auto micros = std::chrono::duration_cast<std::chrono::microseconds>(since).count() % 1'000'000;
  char text[64];
  std::snprintf(text, sizeof text, "%04d%02d%02d%02d%02d%02d.%06lld", tm.tm_year + 1900,
                tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec,
                static_cast<long long>(micros));
  std::string result = text;
  return result.substr(0, result.size() - (6 - decimals));
}

void FakeMicroModem::from_host(std::string_view bytes) {
  if (!booted_) return;  // a modem that is off hears nothing
  for (const std::string& line : host_framer_.push(bytes)) handle_host_line(line);
}

void FakeMicroModem::handle_host_line(const std::string& line) {
  Result<Sentence> sentence = parse_sentence(line, ChecksumRule::kOptional);
  if (!sentence) {
    ++counters_.host_refused;
    // "Bad checksum" is the documented wording (§2.3); the module and the
    // numbers are the fake's choice, NMEA as for other refused input.
    bool checksum = sentence.error().kind == ErrorKind::kBadChecksum;
    later(config_.timing.echo, [this, checksum] {
      report_error("NMEA", checksum ? error_number::kBadChecksum : error_number::kUnparseable,
                   checksum ? "Bad checksum" : "Bad NMEA sentence");
    });
    return;
  }
  ++counters_.host_lines;
  handle_command(*sentence);
}

void FakeMicroModem::handle_command(const Sentence& s) {
  bool mm2 = config_.generation == Generation::kMM2;
  auto echo_later = [this](Sentence reply) { later(config_.timing.echo, [this, reply] { emit(reply); }); };
  if (s.talker != "CC") {
    // fall through to "unknown command"
  } else if (s.type == "CFG") {
    return handle_config(s);
  } else if (s.type == "CFQ") {
    return handle_config_query(s);
  } else if (s.type == "CLK" || s.type == "CLQ" || (mm2 && (s.type == "TMQ" || s.type == "TMS"))) {
    return handle_clock(s);
  } else if (s.type == "CYC") {
    return handle_cycle(s);
  } else if (s.type == "TXD") {
    return handle_transmit_data(s);
  } else if (handle_extra_command(s)) {
    return;
  } else if (mm2 && s.type == "ALQ") {
    // API level 11: an MM2 with $CCTMS (pyacomms' reading, §4.1).
    return echo_later(Sentence{"CA", "ALQ", {"fake_micromodem", "11"}});
  } else if (s.type == "MSC") {
    // Sleep is not simulated: only "0 minutes = reboot now" does anything.
    echo_later(Sentence{"CA", "MSC", s.fields});
    if (s.field(3) == "0") later(config_.timing.echo * 2, [this] { reboot(); });
    return;
  }
  // Wording not public (§5.8): goby3 reads module NMEA as "not known".
  later(config_.timing.echo, [this, name = s.address()] {
    report_error("NMEA", error_number::kUnknownCommand, "Unknown command " + name);
  });
}

void FakeMicroModem::handle_config(const Sentence& s) {
  Result<ConfigParameter> parameter = parse_config_parameter(s);
  auto refuse = [this](std::string what) {
    later(config_.timing.echo, [this, what] {
      report_error("NMEA", error_number::kBadValue, what);
    });
  };
  if (!parameter) return refuse(parameter.error().text);
  if (parameter->name == "ALL") {
    if (parameter->value != "0") return refuse("ALL takes 0");
    nvram_.reset_to_defaults();
    later(config_.timing.nvram_write, [this] { emit(to_sentence(ConfigParameter{"ALL", "0"}, Talker::kModem)); });
    return;
  }
  std::optional<std::string> name = nvram_.write(parameter->name, parameter->value);
  if (!name) return refuse("Bad parameter " + parameter->name + "," + parameter->value);
  // The echo carries the value as stored (canonical integer form, §4.2).
  ConfigParameter stored{*name, *nvram_.read(*name)};
  later(config_.timing.nvram_write, [this, stored] { emit(to_sentence(stored, Talker::kModem)); });
}

void FakeMicroModem::handle_config_query(const Sentence& s) {
  Result<ConfigQuery> query = parse_config_query(s);
  if (!query) {
    later(config_.timing.echo, [this] { report_error("NMEA", error_number::kBadValue, "Bad query"); });
    return;
  }
  if (query->name == "ALL" || query->name == "TOP") {
    // Both names work on both generations (the spec pairs ALL with MM1 and
    // TOP with MM2 without saying that the other is refused). No end
    // marker: the dump simply stops (§4.4).
    Duration at = config_.timing.echo;
    for (const auto& [name, value] : nvram_.all()) {
      ConfigParameter line{name, value};
      later(at, [this, line] { emit(to_sentence(line, Talker::kModem)); });
      at += config_.timing.dump_line;
    }
    return;
  }
  std::optional<std::string> value = nvram_.read(query->name);
  later(config_.timing.echo, [this, name = query->name, value] {
    if (value) {
      emit(to_sentence(ConfigParameter{name, *value}, Talker::kModem));
    } else {
      report_error("NMEA", error_number::kBadValue, "Bad parameter " + name);
    }
  });
}

void FakeMicroModem::handle_clock(const Sentence& s) {
  auto now = water_.scheduler().clock().now();
  auto clock_reply = [this](const char* type) {
    std::tm tm = utc(modem_time_since_epoch());
    ClockTime time{tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec};
    Sentence reply = to_sentence(time, Talker::kModem);
    reply.type = type;
    emit(reply);
  };
  auto iso_time = [this] {
    std::tm tm = utc(modem_time_since_epoch());
    char text[96];
    std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02dZ", tm.tm_year + 1900,
                  tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec);
    return std::string(text);
  };
  auto set_clock = [this, now](std::tm tm) {
    auto set = std::chrono::system_clock::from_time_t(timegm(&tm));
    clock_offset_ = set - now;
  };
  if (s.type == "CLK") {
    Result<ClockTime> time = parse_clock_time(s);
    if (!time) {
      later(config_.timing.echo, [this, text = time.error().text] {
        report_error("NMEA", error_number::kBadValue, text);
      });
      return;
    }
    std::tm tm{};
    tm.tm_year = time->year - 1900, tm.tm_mon = time->month - 1, tm.tm_mday = time->day;
    tm.tm_hour = time->hour, tm.tm_min = time->minute, tm.tm_sec = time->second;
    set_clock(tm);
    later(config_.timing.echo, [clock_reply] { clock_reply("CLK"); });
  } else if (s.type == "CLQ") {
    later(config_.timing.echo, [clock_reply] { clock_reply("CLQ"); });
  } else if (s.type == "TMQ") {
    later(config_.timing.time_query, [this, iso_time] {
      emit(Sentence{"CA", "TMQ", {iso_time(), clock_offset_ ? "USER" : "RTC", "RTC"}});
    });
  } else {  // TMS,<yyyy-mm-ddTHH:MM:SSZ>,<mode>: mode 1 (external PPS) is not simulated
    std::tm tm{};
    std::string text(s.field(1));
    if (std::sscanf(text.c_str(), "%d-%d-%dT%d:%d:%dZ", &tm.tm_year, &tm.tm_mon, &tm.tm_mday,
                    &tm.tm_hour, &tm.tm_min, &tm.tm_sec) != 6) {
      later(config_.timing.echo, [this] { report_error("NMEA", error_number::kBadValue, "Bad time"); });
      return;
    }
    tm.tm_year -= 1900, tm.tm_mon -= 1;
    set_clock(tm);
    later(config_.timing.echo, [this, iso_time] { emit(Sentence{"CA", "TMS", {"0", iso_time()}}); });
  }
}

}  // namespace acomms::fake_micromodem
