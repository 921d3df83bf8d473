#include "iridium/at/at_line.h"

#include <charconv>
#include <optional>
#include <vector>

namespace acomms::iridium {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}

// "0, 41,1 , -1" -> {0, 41, 1, -1}; nullopt if any field is not a number
// or the count differs from `count`.
std::optional<std::vector<int>> fields(std::string_view rest, size_t count) {
  std::vector<int> out;
  while (true) {
    size_t comma = rest.find(',');
    std::string_view field = trim(rest.substr(0, comma));
    if (!field.empty() && field.front() == '+') field.remove_prefix(1);
    int value = 0;
    auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (field.empty() || ec != std::errc() || end != field.data() + field.size()) return std::nullopt;
    out.push_back(value);
    if (out.size() > count) return std::nullopt;
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  if (out.size() != count) return std::nullopt;
  return out;
}

// The fields after `prefix` (which ends with ':'), or nullopt.
std::optional<std::string_view> after(std::string_view line, std::string_view prefix) {
  if (!line.starts_with(prefix)) return std::nullopt;
  return line.substr(prefix.size());
}

}  // namespace

AtLine classify_line(std::string_view line) {
  using Kind = AtLine::Kind;
  AtLine out;
  out.text = std::string(line);
  if (line == "OK") return out.kind = Kind::kOk, out;
  if (line == "ERROR") return out.kind = Kind::kError, out;
  if (line == "READY") return out.kind = Kind::kReady, out;
  if (line == "SBDRING") return out.kind = Kind::kRing, out;
  if (line.size() == 1 && line[0] >= '0' && line[0] <= '9') {
    out.kind = Kind::kDigit;
    out.digit = line[0] - '0';
    return out;
  }
  // +SBDIXA: first: "+SBDIX" is its prefix.
  for (std::string_view prefix : {"+SBDIXA:", "+SBDIX:"}) {
    if (auto rest = after(line, prefix)) {
      auto f = fields(*rest, 6);
      if (!f) return out.kind = Kind::kMalformed, out;
      out.kind = Kind::kSession;
      out.session = {(*f)[0], (*f)[1], (*f)[2], (*f)[3], (*f)[4], (*f)[5], prefix == "+SBDIXA:"};
      return out;
    }
  }
  if (auto rest = after(line, "+SBDSX:")) {
    auto f = fields(*rest, 6);
    if (!f) return out.kind = Kind::kMalformed, out;
    out.kind = Kind::kStatus;
    out.status = {(*f)[0], (*f)[1], (*f)[2], (*f)[3], (*f)[4], (*f)[5], true};
    return out;
  }
  if (auto rest = after(line, "+SBDS:")) {
    auto f = fields(*rest, 4);
    if (!f) return out.kind = Kind::kMalformed, out;
    out.kind = Kind::kStatus;
    out.status = {(*f)[0], (*f)[1], (*f)[2], (*f)[3], 0, 0, false};
    return out;
  }
  for (std::string_view prefix : {"+CSQF:", "+CSQ:"}) {
    if (auto rest = after(line, prefix)) {
      auto f = fields(*rest, 1);
      if (!f || (*f)[0] < 0 || (*f)[0] > 5) return out.kind = Kind::kMalformed, out;
      out.kind = Kind::kSignal;
      out.rssi = (*f)[0];
      return out;
    }
  }
  if (auto rest = after(line, "+CIEV:")) {
    auto f = fields(*rest, 2);
    if (!f) return out.kind = Kind::kMalformed, out;
    out.kind = Kind::kIndicator;
    out.indicator = {(*f)[0], (*f)[1]};
    return out;
  }
  if (line.starts_with("+AREG:")) return out.kind = Kind::kRegistration, out;
  return out;  // kText
}

const char* to_string(AtLine::Kind kind) {
  switch (kind) {
    case AtLine::Kind::kOk: return "OK";
    case AtLine::Kind::kError: return "ERROR";
    case AtLine::Kind::kReady: return "READY";
    case AtLine::Kind::kDigit: return "digit";
    case AtLine::Kind::kSession: return "session result";
    case AtLine::Kind::kStatus: return "buffer status";
    case AtLine::Kind::kSignal: return "signal";
    case AtLine::Kind::kIndicator: return "indicator";
    case AtLine::Kind::kRing: return "ring alert";
    case AtLine::Kind::kRegistration: return "registration";
    case AtLine::Kind::kText: return "text";
    case AtLine::Kind::kMalformed: return "malformed";
  }
  return "?";
}

}  // namespace acomms::iridium
