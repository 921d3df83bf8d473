#pragma once
// Damage the fake modem can do to its own output, on command from a test
// (or the fake_micromodem console): what a real serial line and real
// firmware do to a driver (spec §2.3, §8.6, §10). Each fault is armed and
// then applied to the next line(s) written; bursts are written at once.

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <string_view>

namespace acomms::fake_micromodem {

class FaultInjector {
 public:
  explicit FaultInjector(uint32_t seed = 7) : random_(seed) {}

  // The next `count` lines carry a wrong checksum.
  void corrupt_checksums(int count) { corrupt_ += count; }
  // The next `count` lines are cut in the middle, then terminated (CR LF):
  // what a line looks like when bytes were lost.
  void truncate_lines(int count) { truncate_ += count; }
  // Output is dropped while silent (a hung modem or a cut cable); the
  // modem keeps working behind the silence.
  void set_silent(bool silent) { silent_ = silent; }
  bool silent() const { return silent_; }

  // Applies the armed faults to one complete line (with its CR LF).
  std::string apply(std::string line);

  // Bursts, written straight to the port.
  std::string noise_burst(size_t bytes);                // random bytes, any value
  static std::string overlong_line(size_t characters);  // "$CARXD,...AAAA" + CR LF
  static std::string unknown_sentence();                // well formed, unknown address

 private:
  std::mt19937 random_;
  int corrupt_ = 0;
  int truncate_ = 0;
  bool silent_ = false;
};

}  // namespace acomms::fake_micromodem
