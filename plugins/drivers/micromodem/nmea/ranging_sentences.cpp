#include "micromodem/nmea/ranging_sentences.h"

#include <cmath>

#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/field_reader.h"

namespace acomms::micromodem {

namespace {

constexpr int64_t kMaxHz = 1'000'000;
constexpr int64_t kMaxMs = 1'000'000;
// Longer than any acoustic range a modem reaches (100 km at 1500 m/s).
constexpr double kMaxTravelTime = 100;

std::string n(int64_t value) { return std::to_string(value); }

// Shortest exact form, so what is parsed is what is written again.
std::string seconds_text(double seconds) { return format_real(seconds); }

double travel_time(FieldReader& reader, size_t number, const char* name) {
  double t = reader.real(number, name);
  if (reader.ok() && !(t >= 0 && t <= kMaxTravelTime)) {
    reader.fail(ErrorKind::kBadField, std::string(name) + " '" + reader.text(number) + "' is outside 0..100 s");
  }
  return t;
}

}  // namespace

Sentence to_sentence(const Ping& ping, Talker talker, const char* type) {
  return Sentence{talker == Talker::kHost ? "CC" : "CA", type, {n(ping.source), n(ping.destination)}};
}

Result<Ping> parse_ping(const Sentence& sentence) {
  FieldReader reader(sentence, {"CCMPC", "CAMPC", "CAMPA"});
  reader.require(2);
  Ping ping;
  ping.source = static_cast<int>(reader.integer(1, "SRC", 0, kMaxAddress));
  ping.destination = static_cast<int>(reader.integer(2, "DEST", 0, kMaxAddress));
  return reader.finish(ping);
}

Sentence to_sentence(const PingReply& reply) {
  return Sentence{"CA", "MPR", {n(reply.source), n(reply.destination), seconds_text(reply.travel_time_s)}};
}

Result<PingReply> parse_ping_reply(const Sentence& sentence) {
  FieldReader reader(sentence, {"CAMPR"});
  reader.require(3);
  PingReply reply;
  reply.source = static_cast<int>(reader.integer(1, "SRC", 0, kMaxAddress));
  reply.destination = static_cast<int>(reader.integer(2, "DEST", 0, kMaxAddress));
  reply.travel_time_s = travel_time(reader, 3, "travel time");
  return reader.finish(reply);
}

Sentence to_sentence(const NarrowbandInterrogation& x) {
  Sentence s{"CC", "PNT", {n(x.transmit_frequency_hz), n(x.transmit_ms), n(x.receive_ms), n(x.timeout_ms)}};
  for (int f : x.reply_frequency_hz) s.fields.push_back(n(f));
  s.fields.push_back(x.transmit ? "1" : "0");
  return s;
}

Result<NarrowbandInterrogation> parse_narrowband_interrogation(const Sentence& sentence) {
  FieldReader reader(sentence, {"CCPNT"});
  reader.require(9);
  NarrowbandInterrogation x;
  x.transmit_frequency_hz = static_cast<int>(reader.integer(1, "Ftx", 0, kMaxHz));
  x.transmit_ms = static_cast<int>(reader.integer(2, "Ttx", 0, kMaxMs));
  x.receive_ms = static_cast<int>(reader.integer(3, "Trx", 0, kMaxMs));
  x.timeout_ms = static_cast<int>(reader.integer(4, "Timeout", 0, kMaxMs));
  static const char* const kNames[kTransponders] = {"FA", "FB", "FC", "FD"};
  for (int i = 0; i < kTransponders; ++i) {
    x.reply_frequency_hz[i] = static_cast<int>(reader.integer(5 + i, kNames[i], 0, kMaxHz));
  }
  x.transmit = reader.flag(9, "Tflag");
  return reader.finish(x);
}

Sentence to_sentence(const RemusInterrogation& x) {
  Sentence s{"CC", "PDT",
             {n(x.group), n(x.channel), x.sync_pps ? "1" : "0", n(x.pps_timeout), n(x.timeout_ms)}};
  for (bool listen : x.listen) s.fields.push_back(listen ? "1" : "0");
  return s;
}

Result<RemusInterrogation> parse_remus_interrogation(const Sentence& sentence) {
  FieldReader reader(sentence, {"CCPDT"});
  reader.require(9);
  RemusInterrogation x;
  x.group = static_cast<int>(reader.integer(1, "GRP", 1, 1));
  x.channel = static_cast<int>(reader.integer(2, "CHANNEL", 1, 4));
  x.sync_pps = reader.flag(3, "SF");
  x.pps_timeout = static_cast<int>(reader.integer(4, "STO", 0, kMaxMs));
  x.timeout_ms = static_cast<int>(reader.integer(5, "Timeout", 0, kMaxMs));
  static const char* const kNames[kTransponders] = {"AF", "BF", "CF", "DF"};
  for (int i = 0; i < kTransponders; ++i) x.listen[i] = reader.flag(6 + i, kNames[i]);
  return reader.finish(x);
}

Sentence to_sentence(const TravelTimes& times) {
  Sentence s{"SN", "TTA", {}};
  for (const auto& t : times.travel_time_s) s.fields.push_back(t ? seconds_text(*t) : "");
  s.fields.push_back(times.time);
  return s;
}

Result<TravelTimes> parse_travel_times(const Sentence& sentence) {
  FieldReader reader(sentence, {"SNTTA"});
  reader.require(4);
  TravelTimes times;
  static const char* const kNames[kTransponders] = {"TA", "TB", "TC", "TD"};
  for (int i = 0; i < kTransponders; ++i) {
    if (sentence.field(1 + i).empty()) continue;
    times.travel_time_s[i] = travel_time(reader, 1 + i, kNames[i]);
  }
  times.time = reader.text(5);
  return reader.finish(times);
}

}  // namespace acomms::micromodem
