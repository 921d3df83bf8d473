#include "micromodem/nmea/config_sentences.h"

#include <charconv>
#include <cstdio>

#include "micromodem/nmea/field_reader.h"

namespace acomms::micromodem {
namespace {

std::string talker_code(Talker talker) { return talker == Talker::kHost ? "CC" : "CA"; }

std::string two_digits(int value) {
  char text[16];
  std::snprintf(text, sizeof text, "%02d", value);
  return text;
}

}  // namespace

Sentence to_sentence(const ConfigParameter& parameter, Talker talker) {
  return Sentence{talker_code(talker), "CFG", {parameter.name, parameter.value}};
}

Result<ConfigParameter> parse_config_parameter(const Sentence& sentence) {
  FieldReader reader(sentence, {"CCCFG", "CACFG"});
  reader.require(1);
  if (reader.ok() && sentence.field(1).empty()) {
    reader.fail(ErrorKind::kBadField, sentence.address() + " field 1 (name) is empty");
  }
  // Missing value: an MM2 group header ("$CACFG,psk") prints no value (§4.4).
  // Values are single fields; anything after field 2 is ignored.
  return reader.finish(ConfigParameter{reader.text(1), reader.text(2)});
}

Sentence to_sentence(const ConfigQuery& query) { return Sentence{"CC", "CFQ", {query.name}}; }

Result<ConfigQuery> parse_config_query(const Sentence& sentence) {
  FieldReader reader(sentence, {"CCCFQ"});
  reader.require(1);
  if (reader.ok() && sentence.field(1).empty()) {
    reader.fail(ErrorKind::kBadField, "CCCFQ field 1 (name) is empty");
  }
  return reader.finish(ConfigQuery{reader.text(1)});
}

Sentence to_sentence(const ClockTime& time, Talker talker) {
  return Sentence{talker_code(talker), "CLK",
                  {std::to_string(time.year), two_digits(time.month), two_digits(time.day),
                   two_digits(time.hour), two_digits(time.minute), two_digits(time.second)}};
}

Result<ClockTime> parse_clock_time(const Sentence& sentence) {
  FieldReader reader(sentence, {"CCCLK", "CACLK", "CACLQ"});
  reader.require(6);
  ClockTime time;
  time.year = static_cast<int>(reader.integer(1, "year", 1970, 9999));
  time.month = static_cast<int>(reader.integer(2, "month", 1, 12));
  time.day = static_cast<int>(reader.integer(3, "day", 1, 31));
  time.hour = static_cast<int>(reader.integer(4, "hour", 0, 23));
  time.minute = static_cast<int>(reader.integer(5, "minute", 0, 59));
  time.second = static_cast<int>(reader.integer(6, "second", 0, 60));  // 60: a leap second
  return reader.finish(time);
}

Sentence to_sentence(const Revision& revision) {
  return Sentence{"CA", "REV", {revision.time, revision.identifier, revision.revision}};
}

Result<Revision> parse_revision(const Sentence& sentence) {
  FieldReader reader(sentence, {"CAREV"});
  reader.require(3);
  if (reader.ok() && sentence.field(2).empty()) {
    reader.fail(ErrorKind::kBadField, "CAREV field 2 (identifier) is empty");
  }
  return reader.finish(Revision{reader.text(1), reader.text(2), reader.text(3)});
}

Result<std::vector<int>> revision_numbers(std::string_view revision) {
  std::vector<int> numbers;
  size_t start = 0;
  while (true) {
    size_t dot = revision.find('.', start);
    std::string_view part = revision.substr(start, dot - start);
    int value = 0;
    auto [end, status] = std::from_chars(part.data(), part.data() + part.size(), value);
    if (part.empty() || status != std::errc() || end != part.data() + part.size() || value < 0) {
      return Error{ErrorKind::kBadField,
                   "revision '" + std::string(revision) + "' is not dot-separated numbers"};
    }
    numbers.push_back(value);
    if (dot == std::string_view::npos) break;
    start = dot + 1;
  }
  return numbers;
}

Result<ModemGeneration> modem_generation(std::string_view revision) {
  Result<std::vector<int>> numbers = revision_numbers(revision);
  if (!numbers) return numbers.error();
  int major = numbers->front();
  if (major == 0) return ModemGeneration::kMM1;
  if (major >= 2) return ModemGeneration::kMM2;
  return Error{ErrorKind::kBadField, "revision '" + std::string(revision) +
                                         "' has major 1: neither MM1 (0.x) nor MM2 (2.x and later)"};
}

}  // namespace acomms::micromodem
