#include "micromodem/nmea/time_sentences.h"

#include <charconv>
#include <cstdio>

#include "micromodem/nmea/field_reader.h"

namespace acomms::micromodem {
namespace {

// Digits at text[at, at+count) as a number within [min, max], or -1.
int digits(std::string_view text, size_t at, size_t count, int min, int max) {
  if (at + count > text.size()) return -1;
  int value = 0;
  auto [end, status] = std::from_chars(text.data() + at, text.data() + at + count, value);
  if (status != std::errc() || end != text.data() + at + count || value < min || value > max) return -1;
  return value;
}

}  // namespace

std::string iso_time_text(const ClockTime& t) {
  char text[64];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02dZ", t.year, t.month, t.day, t.hour, t.minute,
                t.second);
  return text;
}

Result<ClockTime> parse_iso_time(std::string_view text) {
  // yyyy-mm-ddTHH:MM:SSZ: exactly 20 characters.
  ClockTime t;
  bool shape = text.size() == 20 && text[4] == '-' && text[7] == '-' && text[10] == 'T' && text[13] == ':' &&
               text[16] == ':' && text[19] == 'Z';
  if (shape) {
    t.year = digits(text, 0, 4, 1970, 9999);
    t.month = digits(text, 5, 2, 1, 12);
    t.day = digits(text, 8, 2, 1, 31);
    t.hour = digits(text, 11, 2, 0, 23);
    t.minute = digits(text, 14, 2, 0, 59);
    t.second = digits(text, 17, 2, 0, 60);  // 60: a leap second
  }
  if (!shape || t.year < 0 || t.month < 0 || t.day < 0 || t.hour < 0 || t.minute < 0 || t.second < 0) {
    return Error{ErrorKind::kBadField, "time '" + std::string(text) + "' is not yyyy-mm-ddTHH:MM:SSZ (UTC)"};
  }
  return t;
}

Sentence to_sentence(const TimeSet& set) {
  return Sentence{"CC", "TMS", {iso_time_text(set.time), std::to_string(set.mode)}};
}

Result<TimeSet> parse_time_set(const Sentence& sentence) {
  FieldReader reader(sentence, {"CCTMS"});
  reader.require(2);
  TimeSet set;
  Result<ClockTime> time = parse_iso_time(sentence.field(1));
  if (reader.ok() && !time) reader.fail(ErrorKind::kBadField, "CCTMS field 1: " + time.error().text);
  if (time) set.time = *time;
  set.mode = static_cast<int>(reader.integer(2, "mode", 0, 1));
  return reader.finish(set);
}

Sentence to_sentence(const TimeSetReply& reply) {
  return Sentence{"CA", "TMS", {reply.timed_out ? "1" : "0", iso_time_text(reply.time)}};
}

Result<TimeSetReply> parse_time_set_reply(const Sentence& sentence) {
  FieldReader reader(sentence, {"CATMS"});
  reader.require(2);
  TimeSetReply reply;
  reply.timed_out = reader.flag(1, "timed out");
  Result<ClockTime> time = parse_iso_time(sentence.field(2));
  if (reader.ok() && !time) reader.fail(ErrorKind::kBadField, "CATMS field 2: " + time.error().text);
  if (time) reply.time = *time;
  return reader.finish(reply);
}

}  // namespace acomms::micromodem
