#include "fault_injector.h"

#include "micromodem/nmea/sentence.h"

namespace acomms::fake_micromodem {

std::string FaultInjector::apply(std::string line) {
  if (corrupt_ > 0) {
    --corrupt_;
    size_t star = line.rfind('*');
    if (star != std::string::npos && star + 2 < line.size()) {
      // Flip the checksum's last digit to another hex digit.
      char& digit = line[star + 2];
      digit = digit == '0' ? '1' : '0';
    }
  }
  if (truncate_ > 0) {
    --truncate_;
    size_t end = line.find('\r');
    line = line.substr(0, end / 2) + "\r\n";
  }
  return line;
}

std::string FaultInjector::noise_burst(size_t bytes) {
  std::uniform_int_distribution<int> byte(0, 255);
  std::string noise(bytes, '\0');
  for (char& c : noise) c = static_cast<char>(byte(random_));
  return noise;
}

std::string FaultInjector::overlong_line(size_t characters) {
  std::string line = "$CARXD,1,2,1,1,";
  if (characters > line.size()) line += std::string(characters - line.size(), 'A');
  return line + "\r\n";
}

std::string FaultInjector::unknown_sentence() {
  return micromodem::serialize(micromodem::Sentence{"CA", "ZZZ", {"1", "fake"}}) + "\r\n";
}

}  // namespace acomms::fake_micromodem
