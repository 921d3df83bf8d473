// The fake modem's extras (spec §6-§7, sequences §8.4-§8.5): the two-way
// ping, narrowband and REMUS LBL against the water's transponders, the
// 13-bit user mini-packet and MM2 FDP packets. Choices where the spec is
// silent are listed in README.md ("Extras").

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fake_micromodem.h"
#include "fake_micromodem_state.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/fdp_sentences.h"
#include "micromodem/nmea/mini_packet_sentences.h"
#include "micromodem/nmea/ranging_sentences.h"
#include "micromodem/nmea/receive_sentences.h"

namespace acomms::fake_micromodem {

using namespace micromodem;

namespace {

Duration seconds(double s) { return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(s)); }

// §3.2: an FDP packet's air time follows its bytes: the mini-frame
// section (up to 96 bytes) then the data section, each in proportion.
Duration fdp_air_time(int rate, size_t bytes) {
  double mini_s = rate == 1 ? 1.574 : rate == 3 ? 0.755 : 0.286;
  double data_s = rate == 5 ? 3.000 : 3.072;
  double mini_bytes = std::min<double>(static_cast<double>(bytes), kFdpMiniFrameBytes);
  double data_bytes = static_cast<double>(bytes) - mini_bytes;
  return seconds(mini_s * mini_bytes / kFdpMiniFrameBytes + data_s * data_bytes / fdp_max_data_bytes(rate));
}

}  // namespace

bool FakeMicroModem::busy() const {
  return exchange_ || transmitting() || awaited_poll_ || water_.scheduler().clock().now() < listening_until_;
}

bool FakeMicroModem::handle_extra_command(const Sentence& s) {
  bool mm2 = config_.generation == Generation::kMM2;
  if (s.type == "MPC") return handle_ping(s), true;
  if (s.type == "MUC") return handle_mini_packet(s), true;
  if (s.type == "PNT" || s.type == "PDT") return handle_lbl(s), true;
  if (mm2 && s.type == "TDP") return handle_fdp(s), true;  // MM1: "Unknown command"
  return false;
}

void FakeMicroModem::handle_ping(const Sentence& s) {
  Result<Ping> ping = parse_ping(s);
  if (!ping) {
    later(config_.timing.echo, [this, text = ping.error().text] { report_error("NMEA", "4", text); });
    return;
  }
  if (busy()) {  // as a $CCCYC while busy (README choice 5)
    later(config_.timing.echo, [this] { report_error("MPC", "1", "Modem busy"); });
    return;
  }
  later(config_.timing.echo, [this, p = *ping] {
    emit(to_sentence(p, Talker::kModem));
    awaited_ping_ = p.destination;
    AcousticPacket packet{PacketKind::kPing, 0, p.source, p.destination, false, 0, {}, {}};
    transmit(packet, config_.timing.mini_air, [] {});
  });
}

void FakeMicroModem::handle_mini_packet(const Sentence& s) {
  Result<MiniPacket> mini = parse_mini_packet(s);
  if (!mini) {
    later(config_.timing.echo, [this, text = mini.error().text] { report_error("NMEA", "4", text); });
    return;
  }
  if (busy()) {
    later(config_.timing.echo, [this] { report_error("MUC", "1", "Modem busy"); });
    return;
  }
  later(config_.timing.echo, [this, m = *mini] {
    emit(to_sentence(m, Talker::kModem));
    std::string bits;
    bits += static_cast<char>(m.value >> 8);
    bits += static_cast<char>(m.value & 0xFF);
    AcousticPacket packet{PacketKind::kMiniPacket, 0, m.source, m.destination, false, 0, {DataFrame{false, bits}}, {}};
    transmit(packet, config_.timing.mini_air, [] {});
  });
}

void FakeMicroModem::handle_fdp(const Sentence& s) {
  Result<FdpTransmit> fdp = parse_fdp_transmit(s);
  if (!fdp) {
    later(config_.timing.echo, [this, text = fdp.error().text] { report_error("NMEA", "4", text); });
    return;
  }
  if (busy()) {
    later(config_.timing.echo, [this] { report_error("TDP", "1", "Modem busy"); });
    return;
  }
  later(config_.timing.echo, [this, f = *fdp] {
    int mini_frames = f.data.empty() ? 0 : 1;
    int data_frames = static_cast<int>(f.data.size()) > kFdpMiniFrameBytes ? 1 : 0;
    emit(to_sentence(FdpEcho{false, std::to_string(next_fdp_id_++), f.destination, f.rate}, mini_frames, data_frames));
    AcousticPacket packet{PacketKind::kFdp, f.rate, address(), f.destination, f.ack,
                          nvram_.integer("psk.packet.mod_hdr_version"), {DataFrame{false, f.data}}, {}};
    later(std::chrono::milliseconds(nvram_.integer("TXD")), [this, packet, f] {
      transmit(packet, fdp_air_time(f.rate, f.data.size()), [] {});
    });
  });
}

void FakeMicroModem::handle_lbl(const Sentence& s) {
  bool narrowband = s.type == "PNT";
  std::array<bool, kTransponders> asked{};
  std::array<int, kTransponders> frequency{};
  int timeout_ms = 0, reply_ms = 0;
  std::string error;
  if (narrowband) {
    auto x = parse_narrowband_interrogation(s);
    if (!x) error = x.error().text;
    else {
      timeout_ms = x->timeout_ms, reply_ms = x->receive_ms, frequency = x->reply_frequency_hz;
      for (int i = 0; i < kTransponders; ++i) asked[i] = frequency[i] != 0;
    }
  } else {
    auto x = parse_remus_interrogation(s);
    if (!x) error = x.error().text;
    else timeout_ms = x->timeout_ms, asked = x->listen;
  }
  if (!error.empty()) {
    later(config_.timing.echo, [this, error] { report_error("NMEA", "4", error); });
    return;
  }
  if (busy()) {
    later(config_.timing.echo, [this, type = s.type] { report_error(type, "1", "Modem busy"); });
    return;
  }
  // The echo: the modem time, then the command's fields (layout not
  // public, §13).
  Sentence echo{"SN", s.type, {modem_time_hhmmss()}};
  echo.fields.insert(echo.fields.end(), s.fields.begin(), s.fields.end());
  later(config_.timing.echo, [this, echo] { emit(echo); });

  // The interrogation leaves now; each transponder that hears it replies
  // after its own turnaround, and the modem reports (round trip - TAT) / 2.
  const double c = water_.settings().sound_speed;
  const double tat = nvram_.integer("TAT") / 1000.0;
  TravelTimes times;
  {
    Duration since = modem_time_since_epoch();
    // long long, not the rep's own type: %lld must match on every ABI.
    long long tenths = std::chrono::duration_cast<std::chrono::milliseconds>(since).count() / 10 % 8'640'000;
    char text[16];
    std::snprintf(text, sizeof text, "%02lld%02lld%02lld.%02lld", tenths / 360000, tenths / 6000 % 60,
                  tenths / 100 % 60, tenths % 100);
    times.time = text;
  }
  double last_s = 0;
  bool all = true;
  for (int i = 0; i < kTransponders; ++i) {
    if (!asked[i]) continue;
    const Transponder* found = nullptr;
    for (const Transponder& t : water_.settings().transponders) {
      bool match = narrowband ? t.kind == Transponder::Kind::kNarrowband && t.reply_frequency_hz == frequency[i]
                              : t.kind == Transponder::Kind::kRemus && t.beacon == "ABCD"[i];
      if (match) found = &t;
    }
    if (found == nullptr || !found->answers) {
      all = false;
      continue;
    }
    double turnaround = std::chrono::duration<double>(found->turnaround).count();
    double round_trip = 2 * distance(config_.position, found->position) / c + turnaround;
    if (round_trip * 1000 > timeout_ms) {  // too late: heard after the modem stopped listening
      all = false;
      continue;
    }
    times.travel_time_s[i] = std::max(0.0, (round_trip - tat) / 2);
    last_s = std::max(last_s, round_trip + reply_ms / 1000.0);
  }
  // $SNTTA at once when every transponder asked for has answered, else
  // after the full Timeout (§7.2; §13 leaves the early case open).
  Duration report = all ? seconds(last_s) : std::chrono::milliseconds(timeout_ms);
  listening_until_ = water_.scheduler().clock().now() + report;
  later(report, [this, times] { emit(to_sentence(times)); });
}

void FakeMicroModem::receive_extra(const AcousticPacket& p, bool damaged) {
  const int own = address();
  if (damaged) {
    emit(to_sentence(TransactionMessage{"BAD_CRC", p.kind == PacketKind::kFdp ? "1" : "2"}));
    return receive_statistics(p, 1, 1);
  }
  switch (p.kind) {
    case PacketKind::kPing:
      if (p.destination != own) return receive_statistics(p, 0, 0);
      emit(to_sentence(Ping{p.source, p.destination}, Talker::kModem, "MPA"));
      receive_statistics(p, 0, 0);
      // The modem replies by itself after its turnaround (§8.4).
      later(config_.timing.turnaround, [this, pinger = p.source] {
        if (transmitting()) return;  // busy: this reply is lost
        AcousticPacket reply{PacketKind::kPingReply, 0, address(), pinger, false, 0, {}, {}};
        transmit(reply, config_.timing.mini_air, [] {});
      });
      return;
    case PacketKind::kPingReply:
      if (p.destination == own && awaited_ping_ == p.source) {
        awaited_ping_.reset();
        // The one-way travel time of the geometry (range / c), not a
        // measured round trip: a sped-up fake's timer jitter would be
        // multiplied by its time scale (README "Extras").
        emit(to_sentence(PingReply{p.source, own, reception_range_m_ / water_.settings().sound_speed}));
      }
      return receive_statistics(p, 0, 0);
    case PacketKind::kMiniPacket: {
      if ((p.destination == own || p.destination == 0) && !p.frames.empty() && p.frames[0].bytes.size() == 2) {
        const std::string& b = p.frames[0].bytes;
        uint32_t value = (static_cast<uint32_t>(static_cast<unsigned char>(b[0])) << 8) |
                         static_cast<unsigned char>(b[1]);
        emit(to_sentence(MiniPacket{p.source, p.destination, value}, Talker::kModem, "MUA"));
      }
      return receive_statistics(p, 0, 0);
    }
    case PacketKind::kFdp: {
      // FDP and legacy PSK headers cannot decode each other (§6): both
      // modems must have psk.packet.mod_hdr_version 1 (frames_wanted
      // carries the sender's). An MM1 cannot decode FDP at all.
      bool decodable = config_.generation == Generation::kMM2 && p.frames_wanted == 1 &&
                       nvram_.integer("psk.packet.mod_hdr_version") == 1;
      if (!decodable) {
        ReceiveStarted unused{};
        (void)unused;
        return receive_statistics(p, 1, 1);  // §8.6: mode 1, PSK error
      }
      FdpReceived rx;
      rx.source = p.source;
      rx.destination = p.destination;
      rx.rate = p.rate;
      rx.ack = p.ack;
      const std::string& data = p.frames.empty() ? std::string() : p.frames[0].bytes;
      size_t mini = std::min<size_t>(data.size(), kFdpMiniFrameBytes);
      if (mini > 0) rx.mini_frames.push_back({true, data.substr(0, mini)});
      if (data.size() > mini) rx.data_frames.push_back({true, data.substr(mini)});
      emit(to_sentence(rx));
      return receive_statistics(p, 0, 0);
    }
    default:
      return;
  }
}

}  // namespace acomms::fake_micromodem
