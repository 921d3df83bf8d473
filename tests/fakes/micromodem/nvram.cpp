#include "nvram.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <stdexcept>

namespace acomms::fake_micromodem {
namespace {

struct Parameter {
  const char* name;
  int default_value;
  int min, max;
  bool mm2_only;
};

// Names from spec §4.3. Defaults: the fake's choice (see README.md), except
// CTO 10 and CST 1, which the spec gives.
constexpr Parameter kParameters[] = {
    {"AGC", 1, 0, 1, false},     {"AGN", 250, 0, 255, false},  {"ASD", 0, 0, 1, false},
    {"BND", 0, 0, 3, false},     {"BR1", 3, 0, 6, false},      {"BR2", 3, 0, 6, false},
    {"BW0", 5000, 0, 50000, false}, {"CRL", 50, 0, 10000, false}, {"CST", 1, 0, 1, false},
    {"CTO", 10, 0, 255, false},  {"DOP", 0, 0, 1, false},      {"DQF", 0, 0, 1, false},
    {"DTO", 2, 0, 255, false},   {"FC0", 25000, 0, 100000, false}, {"HFC", 0, 0, 1, false},
    {"MFD", 0, 0, 1, false},     {"MOD", 0, 0, 1, false},      {"MSE", 0, 0, 1, false},
    {"NRL", 25, 0, 10000, false}, {"NRV", 0, 0, 255, false},   {"PRL", 50, 0, 10000, false},
    {"PTO", 5, 0, 255, false},   {"REV", 1, 0, 1, false},      {"RXA", 0, 0, 1, false},
    {"RXD", 1, 0, 1, false},     {"RXP", 1, 0, 1, false},      {"SHF", 0, 0, 1, false},
    {"SNR", 0, 0, 1, false},     {"SNV", 0, 0, 1, false},      {"SRC", -1, 0, 127, false},
    {"TAT", 50, 0, 10000, false}, {"TOA", 0, 0, 1, false},     {"TXD", 100, 0, 10000, false},
    {"TXF", 1, 0, 1, false},     {"TXP", 1, 0, 1, false},      {"XST", 0, 0, 1, false},
    {"psk.packet.mod_hdr_version", 0, 0, 1, true},
    {"recv.base64data", 0, 0, 1, true},
    {"uart1.bitrate", 19200, 2400, 115200, true},
    {"pwramp.txlevel", 3, 0, 3, true},
    {"xmit.txinhibit", 0, 0, 1, true},
};

const Parameter* find(const std::string& name) {
  for (const Parameter& p : kParameters) {
    if (name == p.name) return &p;
  }
  return nullptr;
}

}  // namespace

Nvram::Nvram(Generation generation, int address) : generation_(generation), address_(address) {
  reset_to_defaults();
}

void Nvram::reset_to_defaults() {
  values_.clear();
  for (const Parameter& p : kParameters) {
    if (p.mm2_only && generation_ != Generation::kMM2) continue;
    // SRC has no factory value worth faking: a fake starts as the node it stands for.
    values_[p.name] = std::to_string(p.default_value < 0 ? address_ : p.default_value);
  }
}

std::optional<std::string> Nvram::canonical(const std::string& name) const {
  std::string upper = name;
  if (name.size() == 3) {
    std::transform(upper.begin(), upper.end(), upper.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  }
  if (!values_.contains(upper)) return std::nullopt;
  return upper;
}

std::optional<std::string> Nvram::write(const std::string& name, const std::string& value) {
  std::optional<std::string> key = canonical(name);
  if (!key) return std::nullopt;
  const Parameter* p = find(*key);
  int number = 0;
  auto [end, status] = std::from_chars(value.data(), value.data() + value.size(), number);
  if (value.empty() || status != std::errc() || end != value.data() + value.size() ||
      number < p->min || number > p->max) {
    return std::nullopt;
  }
  values_[*key] = std::to_string(number);
  return key;
}

std::optional<std::string> Nvram::read(const std::string& name) const {
  std::optional<std::string> key = canonical(name);
  if (!key) return std::nullopt;
  return values_.at(*key);
}

std::vector<std::pair<std::string, std::string>> Nvram::all() const {
  return {values_.begin(), values_.end()};
}

int Nvram::integer(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw std::logic_error("fake NVRAM has no parameter " + name);
  return std::stoi(it->second);
}

}  // namespace acomms::fake_micromodem
