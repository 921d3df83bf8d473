#pragma once
// The fake modem's non-volatile parameters ($CCCFG / $CCCFQ, spec §4.2-4.4).
// They survive a reboot (the clock does not). The defaults are the fake's
// own choice: the public record gives almost none (§13), so they are set
// to make a driver that skips its start-up configuration visibly wrong
// (XST 0: no transmit statistics) while keeping the data path working.

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace acomms::fake_micromodem {

enum class Generation { kMM1, kMM2 };

class Nvram {
 public:
  Nvram(Generation generation, int address);

  // Writes `value` to `name` (three-letter names in any case, MM2 dotted
  // names as given). Values are integers. Returns the canonical name, or
  // nullopt if the name is unknown on this generation or the value is not
  // an integer in range (the modem answers $CAERR then).
  std::optional<std::string> write(const std::string& name, const std::string& value);
  // $CCCFG,ALL,0: every parameter back to its default.
  void reset_to_defaults();
  std::optional<std::string> read(const std::string& name) const;
  // Every parameter in dump order ($CCCFQ,ALL / TOP).
  std::vector<std::pair<std::string, std::string>> all() const;

  int integer(const std::string& name) const;  // REQUIRES: a known name
  bool flag(const std::string& name) const { return integer(name) != 0; }

 private:
  std::optional<std::string> canonical(const std::string& name) const;
  Generation generation_;
  int address_;
  std::map<std::string, std::string> values_;
};

}  // namespace acomms::fake_micromodem
