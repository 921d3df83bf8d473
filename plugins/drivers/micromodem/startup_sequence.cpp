#include "micromodem/startup_sequence.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <stdexcept>

#include "core/core_thread.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;
using nmea::Sentence;
using nmea::Talker;

std::vector<ConfigParameter> driver_settings() {
  return {
      {"CST", "1"},  // $CACST after every reception: receive aggregation and link figures
      {"XST", "1"},  // $CAXST after every transmission: the transmit result
      {"REV", "1"},  // $CAREV at boot and periodically: reboot detection
      {"RXP", "1"},  // $CARXP: a reception starts
      {"TXP", "1"},  // $CATXP / $CATXF: a transmission starts / ends
      {"TXF", "1"},
      {"RXD", "1"},  // $CARXD: with 0 no data reaches the host
      {"ASD", "0"},  // never transmit test data when the host has none
  };
}

namespace {

std::string trim(std::string_view text) {
  size_t begin = text.find_first_not_of(" \t");
  if (begin == std::string_view::npos) return "";
  size_t end = text.find_last_not_of(" \t");
  return std::string(text.substr(begin, end - begin + 1));
}

std::optional<long long> as_integer(std::string_view text) {
  long long value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return value;
}

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

ConfigParameter parse_cfg_entry(const std::string& entry) {
  size_t comma = entry.find(',');
  std::string name = trim(std::string_view(entry).substr(0, comma));
  std::string value = comma == std::string::npos ? "" : trim(std::string_view(entry).substr(comma + 1));
  bool name_ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_';
  });
  bool value_ok = !value.empty() && std::all_of(value.begin(), value.end(), [](char c) {
    return c >= 0x20 && c <= 0x7e && c != ',' && c != '*' && c != '$';
  });
  if (comma == std::string::npos || !name_ok || !value_ok) {
    throw std::invalid_argument("driver.micromodem.cfg \"" + entry +
                                "\": expected \"KEY,VALUE\" (e.g. \"BND,3\"; a name of letters, digits and dots, "
                                "a value without ',', '*' or '$')");
  }
  if (name.size() == 3 && name.find('.') == std::string::npos) {
    std::transform(name.begin(), name.end(), name.begin(), [](char c) { return std::toupper(c); });
  }
  return {name, value};
}

bool confirms(const ConfigParameter& wanted, const ConfigParameter& echo) {
  if (!same_name(wanted.name, echo.name)) return false;
  auto a = as_integer(wanted.value), b = as_integer(echo.value);
  if (a && b) return *a == *b;
  return wanted.value == echo.value;
}

StartupSequence::StartupSequence(CommandQueue& commands, core::Scheduler& scheduler, Options options,
                                 std::function<void(const std::string&)> done)
    : commands_(commands), scheduler_(scheduler), options_(std::move(options)), done_(std::move(done)) {
  settings_.push_back({"SRC", std::to_string(options_.own_id)});
  for (ConfigParameter& p : driver_settings()) settings_.push_back(std::move(p));
  for (const ConfigParameter& p : options_.user_cfg) settings_.push_back(p);
}

StartupSequence::~StartupSequence() {
  *alive_ = false;
  if (timer_ != 0) scheduler_.cancel(timer_);
}

void StartupSequence::begin() {
  ACOMMS_ASSERT_CORE_THREAD();
  listening_ = true;
  timer_ = scheduler_.after(options_.listen, [this] {
    timer_ = 0;
    if (listening_) probe();
  });
}

void StartupSequence::on_revision(const Revision& revision) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (revision.identifier != "AUV") return;
  auto generation = nmea::modem_generation(revision.revision);
  if (generation) generation_ = *generation;
  revision_ = revision.revision;
  if (!listening_) return;
  listening_ = false;
  if (timer_ != 0) scheduler_.cancel(timer_);
  timer_ = 0;
  write_settings();
}

void StartupSequence::probe() {
  // REV=0 modems print no $CAREV: a query of SRC tells us it is alive.
  listening_ = false;
  std::weak_ptr<bool> alive = alive_;
  commands_.push({to_sentence(nmea::ConfigQuery{"SRC"}),
                  [](const Sentence& s) { return s.is("CACFG") && s.field(1) == "SRC"; },
                  [this, alive](bool ok, const Sentence*, const std::string& why) {
                    if (alive.expired()) return;
                    if (!ok) return fail("the modem did not answer: no $CAREV and " + why + " to $CCCFQ,SRC");
                    write_settings();
                  }});
}

void StartupSequence::write_settings() { write_next(0); }

void StartupSequence::write_next(size_t index) {
  if (finished_) return;
  if (index == settings_.size()) return set_clock();
  const ConfigParameter wanted = settings_[index];
  std::weak_ptr<bool> alive = alive_;
  commands_.push({to_sentence(wanted, Talker::kHost),
                  [wanted](const Sentence& s) {
                    if (!s.is("CACFG")) return false;
                    auto echo = nmea::parse_config_parameter(s);
                    return echo && confirms(wanted, *echo);
                  },
                  [this, alive, wanted, index](bool ok, const Sentence*, const std::string& why) {
                    if (alive.expired()) return;
                    if (!ok) return fail("NVRAM setting " + wanted.name + "," + wanted.value + " not applied: " + why);
                    write_next(index + 1);
                  }});
}

void StartupSequence::set_clock() {
  // MM2 is set with $CCTMS (goby3 does so; §4.5), MM1 with $CCCLK. A modem
  // whose revision was not printed (REV=0, or it booted before the port
  // opened) gets $CCCLK and, if it refuses that, $CCTMS.
  set_clock_at_next_second(generation_ == ModemGeneration::kMM2, !generation_);
}

void StartupSequence::set_clock_at_next_second(bool time_set, bool fall_back) {
  // Just after a UTC second boundary, carrying the next second (spec §4.5).
  using namespace std::chrono;
  auto now = scheduler_.clock().now();
  auto next_second = time_point_cast<seconds>(now) + seconds(1);
  auto send_at = next_second + milliseconds(50);
  std::weak_ptr<bool> alive = alive_;
  timer_ = scheduler_.at(send_at, [this, alive, next_second, time_set, fall_back] {
    timer_ = 0;
    auto carried = next_second + seconds(1);
    std::time_t t = system_clock::to_time_t(time_point_cast<system_clock::duration>(carried));
    std::tm utc{};
    gmtime_r(&t, &utc);
    nmea::ClockTime clock{utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec};
    if (time_set) return set_clock_mm2(clock);
    commands_.push({to_sentence(clock, Talker::kHost), [](const Sentence& s) { return s.is("CACLK"); },
                    [this, alive, fall_back](bool ok, const Sentence*, const std::string& why) {
                      if (alive.expired()) return;
                      if (!ok && fall_back) {
                        spdlog::info("start-up: $CCCLK not taken ({}); trying $CCTMS (MM2)", why);
                        return set_clock_at_next_second(true, false);
                      }
                      if (!ok) return fail("the clock was not set: " + why);
                      finished_ = true;
                      done_("");
                    }});
  });
}

void StartupSequence::fail(const std::string& why) {
  if (finished_) return;
  finished_ = true;
  done_("start-up failed: " + why);
}

}  // namespace acomms::drivers::micromodem
