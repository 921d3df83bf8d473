#include "micromodem/nmea/statistics_sentences.h"

#include <climits>
#include <tuple>

#include "micromodem/nmea/field_reader.h"

namespace acomms::micromodem {
namespace {

// Reads field `number` of the versioned layout from a line that may lack
// the version field (v0: every field one place earlier).
class LayoutReader {
 public:
  LayoutReader(FieldReader& reader, bool versioned) : reader_(reader), shift_(versioned ? 0 : 1) {}
  int integer(size_t number, std::string_view name, int absent = 0) {
    return static_cast<int>(
        reader_.optional_integer(number - shift_, name, INT_MIN, INT_MAX).value_or(absent));
  }
  double real(size_t number, std::string_view name) {
    return reader_.optional_real(number - shift_, name).value_or(0);
  }
  std::string text(size_t number) { return reader_.text(number - shift_); }

 private:
  FieldReader& reader_;
  size_t shift_;
};

std::string n(int value) { return std::to_string(value); }

auto comparable(const ReceiveStatistics& s) {
  return std::tie(s.version, s.mode, s.time_of_arrival, s.clock_status, s.mf_peak, s.mf_power,
                  s.mf_ratio, s.spl, s.analog_gain, s.shift_previous, s.shift_current,
                  s.shift_detect, s.shift_baseband, s.rate, s.source, s.destination, s.psk_error,
                  s.packet_type, s.frames, s.bad_frames, s.rss, s.snr_in, s.snr_out, s.snr_symbol,
                  s.mse, s.dqf, s.doppler, s.noise, s.carrier, s.bandwidth, s.sequence,
                  s.data_rate, s.data_frames, s.bad_data_frames);
}

auto comparable(const TransmitStatistics& s) {
  return std::tie(s.version, s.date, s.time, s.clock_status, s.mode, s.probe_length, s.bandwidth,
                  s.carrier, s.rate, s.source, s.destination, s.ack, s.frames_expected,
                  s.frames_sent, s.packet_type, s.bytes, s.carrier_used);
}

}  // namespace

bool ReceiveStatistics::operator==(const ReceiveStatistics& other) const {
  return comparable(*this) == comparable(other);
}

bool TransmitStatistics::operator==(const TransmitStatistics& other) const {
  return comparable(*this) == comparable(other);
}

Sentence to_sentence(const ReceiveStatistics& s) {
  Sentence sentence{"CA", "CST", {}};
  auto& f = sentence.fields;
  if (s.version != 0) f.push_back(n(s.version));
  f.insert(f.end(), {n(s.mode), s.time_of_arrival, n(s.clock_status), n(s.mf_peak),
                     n(s.mf_power), n(s.mf_ratio), n(s.spl), n(s.analog_gain),
                     n(s.shift_previous), n(s.shift_current), n(s.shift_detect),
                     n(s.shift_baseband), n(s.rate), n(s.source), n(s.destination),
                     n(s.psk_error), n(s.packet_type), n(s.frames), n(s.bad_frames),
                     format_real(s.rss), format_real(s.snr_in), format_real(s.snr_out),
                     format_real(s.snr_symbol), format_real(s.mse), n(s.dqf),
                     format_real(s.doppler), format_real(s.noise), n(s.carrier),
                     n(s.bandwidth)});
  if (s.version >= 7) {
    f.insert(f.end(), {n(s.sequence), n(s.data_rate), n(s.data_frames), n(s.bad_data_frames)});
  }
  return sentence;
}

Result<ReceiveStatistics> parse_receive_statistics(const Sentence& sentence) {
  FieldReader reader(sentence, {"CACST"});
  reader.require(2);
  // Version 0 has no version field: its field 1 is the mode (0..2).
  int first = static_cast<int>(reader.integer(1, "version or mode", INT_MIN, INT_MAX));
  bool versioned = first >= 6;
  LayoutReader layout(reader, versioned);
  ReceiveStatistics s;
  s.version = versioned ? first : 0;
  s.mode = layout.integer(2, "mode");
  s.time_of_arrival = layout.text(3);
  s.clock_status = layout.integer(4, "clock status");
  s.mf_peak = layout.integer(5, "matched-filter peak");
  s.mf_power = layout.integer(6, "matched-filter power");
  s.mf_ratio = layout.integer(7, "matched-filter ratio");
  s.spl = layout.integer(8, "SPL");
  s.analog_gain = layout.integer(9, "analog gain");
  s.shift_previous = layout.integer(10, "shift previous");
  s.shift_current = layout.integer(11, "shift current");
  s.shift_detect = layout.integer(12, "shift detect");
  s.shift_baseband = layout.integer(13, "shift baseband");
  s.rate = layout.integer(14, "rate");
  s.source = layout.integer(15, "source");
  s.destination = layout.integer(16, "destination");
  s.psk_error = layout.integer(17, "PSK error");
  s.packet_type = layout.integer(18, "packet type", kPacketUnknown);
  s.frames = layout.integer(19, "frames");
  s.bad_frames = layout.integer(20, "bad frames");
  s.rss = layout.real(21, "RSS");
  s.snr_in = layout.real(22, "input SNR");
  s.snr_out = layout.real(23, "output SNR");
  s.snr_symbol = layout.real(24, "symbol SNR");
  s.mse = layout.real(25, "MSE");
  s.dqf = layout.integer(26, "DQF");
  s.doppler = layout.real(27, "Doppler");
  s.noise = layout.real(28, "noise");
  s.carrier = layout.integer(29, "carrier");
  s.bandwidth = layout.integer(30, "bandwidth");
  if (s.version >= 7) {  // older layouts have no FDP fields: ignore any extra
    s.sequence = layout.integer(31, "sequence", -1);
    s.data_rate = layout.integer(32, "data-frame rate", -1);
    s.data_frames = layout.integer(33, "data frames", -1);
    s.bad_data_frames = layout.integer(34, "bad data frames", -1);
  }
  s.field_count = sentence.fields.size();
  return reader.finish(s);
}

Sentence to_sentence(const TransmitStatistics& s) {
  Sentence sentence{"CA", "XST", {}};
  auto& f = sentence.fields;
  if (s.version != 0) f.push_back(n(s.version));
  f.insert(f.end(), {s.date, s.time, n(s.clock_status), n(s.mode), n(s.probe_length),
                     n(s.bandwidth), n(s.carrier), n(s.rate), n(s.source), n(s.destination),
                     s.ack ? "1" : "0", n(s.frames_expected), n(s.frames_sent),
                     n(s.packet_type), n(s.bytes)});
  if (s.version >= 7) f.push_back(n(s.carrier_used));
  return sentence;
}

Result<TransmitStatistics> parse_transmit_statistics(const Sentence& sentence) {
  FieldReader reader(sentence, {"CAXST"});
  reader.require(2);
  // Version 0 has no version field: its field 1 is the date (yyyymmdd).
  // A first field of 0 or less is read as a (nonsense) date too, so that
  // version 0 is never written as a version field.
  int first = static_cast<int>(reader.integer(1, "version or date", INT_MIN, INT_MAX));
  bool versioned = first > 0 && first <= 19700000;
  LayoutReader layout(reader, versioned);
  TransmitStatistics s;
  s.version = versioned ? first : 0;
  s.date = layout.text(2);
  s.time = layout.text(3);
  s.clock_status = layout.integer(4, "clock status");
  s.mode = layout.integer(5, "mode");
  s.probe_length = layout.integer(6, "probe length");
  s.bandwidth = layout.integer(7, "bandwidth");
  s.carrier = layout.integer(8, "carrier");
  s.rate = layout.integer(9, "rate");
  s.source = layout.integer(10, "source");
  s.destination = layout.integer(11, "destination");
  s.ack = layout.integer(12, "ACK") != 0;
  s.frames_expected = layout.integer(13, "frames expected");
  s.frames_sent = layout.integer(14, "frames sent");
  s.packet_type = layout.integer(15, "packet type", kPacketUnknown);
  s.bytes = layout.integer(16, "bytes");
  if (s.version >= 7) s.carrier_used = layout.integer(17, "carrier used");
  s.field_count = sentence.fields.size();
  return reader.finish(s);
}

}  // namespace acomms::micromodem
