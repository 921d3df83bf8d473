#include "link/raw_log.h"

#include <cstdio>
#include <ctime>
#include <stdexcept>
#include <system_error>

#include "util/hex.h"

namespace acomms::link {

RawLog::RawLog(std::filesystem::path path, uint64_t max_bytes, const core::Clock& clock)
    : path_(std::move(path)), max_bytes_(max_bytes == 0 ? 1 : max_bytes), clock_(clock) {
  open();
}

void RawLog::open() {
  file_.open(path_, std::ios::app | std::ios::binary);
  if (!file_) throw std::runtime_error("cannot open the raw link log " + path_.string());
  std::error_code ec;
  auto size = std::filesystem::file_size(path_, ec);
  size_ = ec ? 0 : size;
}

std::string RawLog::format(core::Clock::time_point at, std::string_view bytes, bool outgoing) {
  using namespace std::chrono;
  auto micros = duration_cast<microseconds>(at.time_since_epoch()).count();
  std::time_t seconds = static_cast<std::time_t>(micros / 1'000'000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char stamp[48];
  std::snprintf(stamp, sizeof stamp, "%04d-%02d-%02dT%02d:%02d:%02d.%06lldZ", utc.tm_year + 1900, utc.tm_mon + 1,
                utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, static_cast<long long>(micros % 1'000'000));
  std::string line = stamp;
  line += outgoing ? " >> " : " << ";
  for (char c : bytes) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7f && c != '\\') {
      line += c;
    } else {
      line += "\\x";
      line += util::hex_encode(std::string_view(&c, 1), util::HexCase::kUpper);
    }
  }
  return line;
}

void RawLog::record(std::string_view bytes, bool outgoing) {
  std::string line = format(clock_.now(), bytes, outgoing) + "\n";
  if (size_ > 0 && size_ + line.size() > max_bytes_) rotate();
  file_ << line;
  file_.flush();  // a crash must not lose what the modem said last
  size_ += line.size();
}

void RawLog::rotate() {
  file_.close();
  std::error_code ec;
  std::filesystem::rename(path_, path_.string() + ".1", ec);  // replaces the older one
  ++rotations_;
  file_.open(path_, std::ios::trunc | std::ios::binary);
  if (!file_) throw std::runtime_error("cannot reopen the raw link log " + path_.string());
  size_ = 0;
}

}  // namespace acomms::link
