// The fake modem's receive side (spec §5.6-5.7, §8): an arrival is
// detected ($CARXP), decoded after its air time, and printed as a real
// modem prints it; the modem itself acknowledges packets addressed to it.

#include <algorithm>
#include <cmath>

#include "fake_micromodem.h"
#include "fake_micromodem_state.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/statistics_sentences.h"

namespace acomms::fake_micromodem {

using namespace micromodem;

void FakeMicroModem::on_arrival(const AcousticPacket& packet, Duration air, double range_m) {
  if (!booted_) return;
  if (transmitting()) {  // half duplex: a transmitting modem hears nothing
    ++counters_.collisions;
    return;
  }
  if (reception_) {
    // Overlapping arrivals: the first is damaged, the second never detected
    // (the spec allows "as damaged, or nothing", §8.6).
    reception_->damaged = true;
    ++counters_.collisions;
    return;
  }
  reception_ = std::make_unique<Reception>();
  reception_->id = next_reception_id_++;
  reception_->packet = packet;
  reception_->range_m = range_m;
  if (nvram_.flag("RXP")) emit(to_sentence(ReceiveStarted{packet.is_psk(nvram_.flag("MOD")) ? 1 : 0}));
  uint64_t id = reception_->id;
  later(air + config_.timing.decode, [this, id] {
    if (reception_ && reception_->id == id) finish_reception();
  });
}

void FakeMicroModem::finish_reception() {
  std::unique_ptr<Reception> done = std::move(reception_);
  reception_range_m_ = done->range_m;
  ++counters_.receptions;
  switch (done->packet.kind) {
    case PacketKind::kCycleInit:
      if (done->damaged) {
        emit(to_sentence(TransactionMessage{"BAD_CRC", "2"}));  // 2: a mini-packet (MOOS)
        return receive_statistics(done->packet, 1, 1);
      }
      return receive_cycle_init(done->packet);
    case PacketKind::kData:
      return receive_data(done->packet, done->damaged);
    case PacketKind::kAck:
      if (done->damaged) {
        emit(to_sentence(TransactionMessage{"BAD_CRC", "2"}));
        return receive_statistics(done->packet, 1, 1);
      }
      return receive_ack(done->packet);
    default:
      return receive_extra(done->packet, done->damaged);
  }
}

void FakeMicroModem::receive_cycle_init(const AcousticPacket& p) {
  Cycle cycle{0, p.source, p.destination, p.rate, p.ack, p.frames_wanted};
  // Every modem that decodes a cycle-init prints it (§5.1).
  emit(to_sentence(cycle, Talker::kModem));
  receive_statistics(p, 0, 0);
  // A poll for this modem (ADR1 = our SRC): it requests the frames from
  // its host (§8.2). A busy modem ignores the poll (the spec is silent).
  if (p.source == address() && !exchange_ && !transmitting() && !awaited_poll_) {
    start_exchange(cycle, true);
  }
}

void FakeMicroModem::receive_data(const AcousticPacket& p, bool damaged) {
  std::bernoulli_distribution header_error(config_.header_error_probability);
  if (p.is_psk(nvram_.flag("MOD")) && config_.header_error_probability > 0 && header_error(random_)) {
    // An undecodable PSK header (§8.6): nothing but the statistics, mode 1,
    // PSK error 1; the modem learned neither the cycle nor the frames.
    return receive_statistics(p, 1, 0, true);
  }
  if (p.rate > 0) {
    // PSK packets carry the cycle in their header: printed again (§5.1 c).
    emit(to_sentence(Cycle{0, p.source, p.destination, p.rate, p.ack, p.frames_wanted}, Talker::kModem));
  }
  std::bernoulli_distribution frame_error(config_.frame_error_probability);
  int bad = 0;
  std::vector<int> to_ack;
  for (size_t i = 0; i < p.frames.size(); ++i) {
    int number = static_cast<int>(i) + 1;
    const DataFrame& frame = p.frames[i];
    if (damaged || frame_error(random_)) {
      ++bad;
      // In place of the frame's $CARXD, in frame order (§10 quirk 16).
      emit(to_sentence(TransactionMessage{"BAD_CRC", "1"}));
      continue;
    }
    if (nvram_.flag("RXD")) emit(to_sentence(ReceivedData{p.source, p.destination, frame.ack, number, frame.bytes}));
    if (frame.ack) to_ack.push_back(number);
  }
  receive_statistics(p, bad > 0 ? 1 : 0, bad);
  if (awaited_poll_ && awaited_poll_->second == p.source) awaited_poll_.reset();
  // Only the addressed modem acknowledges; never a broadcast (§5.7, §8.3).
  if (p.destination == address() && p.destination != 0 && !to_ack.empty()) {
    send_ack(p, std::move(to_ack));
  }
}

void FakeMicroModem::send_ack(const AcousticPacket& data, std::vector<int> frames) {
  AcousticPacket ack{PacketKind::kAck, data.rate, address(), data.source, false, 0, {}, {}};
  ack.acked_frames = std::move(frames);
  later(config_.timing.turnaround, [this, ack] {
    if (transmitting()) return;  // busy: this acknowledgement is lost
    transmit(ack, config_.timing.mini_air, [] {});
  });
}

void FakeMicroModem::receive_ack(const AcousticPacket& p) {
  int own = address();
  bool for_us = p.destination == own;
  // MM1 bug (§10 quirk 8): third-party ACKs reported as if for us.
  bool bug = config_.third_party_ack_bug && config_.generation == Generation::kMM1 && p.source != own;
  if (for_us || bug) {
    for (int frame : p.acked_frames) {
      emit(to_sentence(Acknowledgement{p.source, for_us ? p.destination : own, frame}));
    }
  }
  receive_statistics(p, 0, 0);
}

void FakeMicroModem::receive_statistics(const AcousticPacket& p, int mode, int bad_frames, bool header_lost) {
  if (!nvram_.flag("CST")) return;
  bool mm1 = config_.generation == Generation::kMM1;
  bool psk = p.is_psk(nvram_.flag("MOD"));
  ReceiveStatistics s;
  s.version = mm1 ? 6 : 8;
  s.mode = mode;
  s.time_of_arrival = modem_date_time(mm1 ? 4 : 6);
  s.clock_status = clock_offset_ ? 1 : 0;
  if (mode != 2) {  // a packet timeout's other fields are meaningless (§5.6)
    // Invented but plausible levels: spherical spreading from a 185 dB
    // source over a noise floor of 85 dB, so SNR falls with range.
    double range = std::max(1.0, reception_range_m_);
    double spl = 185 - 20 * std::log10(range);
    s.mf_peak = 32767;
    s.mf_power = static_cast<int>(spl - 100);
    s.mf_ratio = 100;
    s.spl = static_cast<int>(spl);
    s.analog_gain = nvram_.integer("AGN");
    s.rate = p.rate;
    s.source = p.source;
    s.destination = p.destination;
    s.psk_error = psk && bad_frames > 0 ? 3 : 0;
    s.packet_type = p.kind == PacketKind::kFdp ? kPacketFdp
                    : p.is_mini()                ? (psk ? kPacketPskMini : kPacketFskMini)
                                                 : (psk ? kPacketPsk : kPacketFsk);
    s.frames = p.is_mini() ? 1 : static_cast<int>(p.frames.size());
    s.bad_frames = bad_frames;
    s.rss = std::round(spl);
    s.snr_in = std::round((spl - 85) * 10) / 10;
    s.snr_out = psk ? std::round((spl - 90) * 10) / 10 : 0;
    s.mse = psk ? -std::round((spl - 90) / 2 * 10) / 10 : 0;
    s.dqf = psk ? 0 : 200;
    s.noise = 85;
    s.carrier = nvram_.integer("FC0");
    s.bandwidth = nvram_.integer("BW0");
    if (header_lost) {
      // What the header would have said is unknown: the fake writes -1 for
      // source and destination (the spec does not say what a modem writes)
      // and no frames.
      s.source = -1;
      s.destination = -1;
      s.psk_error = 1;
      s.frames = 0;
      s.bad_frames = 0;
    }
  }
  emit(to_sentence(s));
}

}  // namespace acomms::fake_micromodem
