#pragma once
// A test's view of one fake Micro-Modem's serial port: everything the modem
// writes, framed and parsed, each line stamped with the simulated time it
// was written; and a way to type host commands.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fake_micromodem.h"
#include "micromodem/nmea/line_framer.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::fake_micromodem {

struct HeardLine {
  core::Clock::time_point at;
  micromodem::Sentence sentence;
};

class FakeModemHost {
 public:
  FakeModemHost(FakeMicroModem& modem, const core::Clock& clock) : modem_(modem), clock_(clock) {
    modem_.set_output([this](std::string_view bytes) {
      raw_ += bytes;
      for (const std::string& line : framer_.push(bytes)) {
        auto sentence = micromodem::parse_sentence(line);
        if (sentence) {
          lines_.push_back({clock_.now(), *sentence});
        } else {
          refused_.push_back(sentence.error());
        }
      }
    });
  }

  void send(const micromodem::Sentence& sentence) {
    modem_.from_host(micromodem::serialize(sentence) + "\r\n");
  }
  void send_raw(std::string_view bytes) { modem_.from_host(bytes); }

  const std::vector<HeardLine>& lines() const { return lines_; }
  const std::vector<micromodem::Error>& refused() const { return refused_; }
  const std::string& raw() const { return raw_; }
  void clear() { lines_.clear(); refused_.clear(); raw_.clear(); }

  // Addresses of the lines heard so far, in order ("CACYC", "CADRQ", ...).
  std::vector<std::string> addresses() const {
    std::vector<std::string> out;
    for (const HeardLine& line : lines_) out.push_back(line.sentence.address());
    return out;
  }
  // The first line with `address`, or nullptr.
  const HeardLine* first(std::string_view address) const {
    for (const HeardLine& line : lines_) {
      if (line.sentence.is(address)) return &line;
    }
    return nullptr;
  }
  size_t count(std::string_view address) const {
    size_t n = 0;
    for (const HeardLine& line : lines_) n += line.sentence.is(address) ? 1 : 0;
    return n;
  }

 private:
  FakeMicroModem& modem_;
  const core::Clock& clock_;
  micromodem::LineFramer framer_;
  std::vector<HeardLine> lines_;
  std::vector<micromodem::Error> refused_;
  std::string raw_;
};

}  // namespace acomms::fake_micromodem
