// The fake modem's transmit side (spec §5.1-5.5, §8.1-8.3): $CCCYC, the
// $CADRQ / $CCTXD exchange, data timeouts, and putting packets in the water
// with $CATXP / $CATXF / $CAXST around them.

#include <algorithm>

#include "fake_micromodem.h"
#include "fake_micromodem_state.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/statistics_sentences.h"

namespace acomms::fake_micromodem {

using namespace micromodem;

bool FakeMicroModem::transmitting() const {
  return water_.scheduler().clock().now() < transmitting_until_;
}

void FakeMicroModem::handle_cycle(const Sentence& s) {
  Result<Cycle> cycle = parse_cycle(s);
  if (!cycle) {
    later(config_.timing.echo, [this, text = cycle.error().text] { report_error("NMEA", "4", text); });
    return;
  }
  if (exchange_ || transmitting() || awaited_poll_) {
    // The spec leaves a $CCCYC during a cycle open (§13); this fake refuses
    // it with an error and no echo, so a driver that sends one sees it.
    later(config_.timing.echo, [this] { report_error("CYC", "1", "Modem busy"); });
    return;
  }
  Cycle c = *cycle;
  later(config_.timing.echo, [this, c] {
    emit(to_sentence(c, Talker::kModem));
    if (c.source == address()) {
      if (c.rate == 0) {
        // Rate 0: the cycle-init mini-packet goes first; $CADRQ follows
        // its $CAXST (§5.2).
        AcousticPacket init{PacketKind::kCycleInit, c.rate, c.source, c.destination, c.ack, c.frames, {}, {}};
        transmit(init, config_.timing.mini_air, [this, c] { start_exchange(c, false); });
      } else {
        start_exchange(c, false);
      }
      return;
    }
    // Third-party poll: ask ADR1 to send, then wait for its packet.
    AcousticPacket poll{PacketKind::kCycleInit, c.rate, c.source, c.destination, c.ack, c.frames, {}, {}};
    uint64_t id = next_poll_id_++;
    awaited_poll_ = {id, c.source};
    transmit(poll, config_.timing.mini_air, [this, id] {
      later(std::chrono::seconds(nvram_.integer("CTO")), [this, id] { poll_timeout(id); });
    });
  });
}

void FakeMicroModem::poll_timeout(uint64_t poll_id) {
  if (!awaited_poll_ || awaited_poll_->first != poll_id) return;
  awaited_poll_.reset();
  // The value after PACKET_TIMEOUT is not public: the fake writes 0.
  emit(to_sentence(TransactionMessage{"PACKET_TIMEOUT", "0"}));
  AcousticPacket nothing;
  receive_statistics(nothing, 2, 0);
}

void FakeMicroModem::start_exchange(const Cycle& cycle, bool polled) {
  exchange_ = std::make_unique<Exchange>();
  exchange_->id = next_exchange_id_++;
  exchange_->cycle = cycle;
  exchange_->polled = polled;
  // Nframes is capped by the rate; 0 is taken as 1 (the spec is silent).
  exchange_->frames_wanted = std::clamp(cycle.frames, 1, kRates[cycle.rate].frames);
  request_frame();
}

void FakeMicroModem::request_frame() {
  Exchange& x = *exchange_;
  int frame = static_cast<int>(x.frames.size()) + 1;
  x.awaiting_frame = true;
  if (!buffered_frames_.empty()) {
    // A $CCTXD that came when no $CADRQ was outstanding is sent with the
    // next cycle (§5.3, firmware FIFO): it answers this request at once,
    // without a $CADRQ being printed.
    TransmitData late = buffered_frames_.front();
    buffered_frames_.erase(buffered_frames_.begin());
    accept_frame(late);
    return;
  }
  emit(to_sentence(DataRequest{modem_time_hhmmss(), x.cycle.source, x.cycle.destination,
                               x.cycle.ack, kRates[x.cycle.rate].frame_bytes, frame}));
  uint64_t id = x.id;
  later(std::chrono::seconds(nvram_.integer("DTO")), [this, id, frame] { data_timeout(id, frame); });
}

void FakeMicroModem::handle_transmit_data(const Sentence& s) {
  Result<TransmitData> frame = parse_transmit_data(s);
  if (!frame) {
    later(config_.timing.echo, [this, text = frame.error().text] { report_error("NMEA", "4", text); });
    return;
  }
  if (!exchange_ || !exchange_->awaiting_frame) {
    buffered_frames_.push_back(*frame);
    return;
  }
  int limit = kRates[exchange_->cycle.rate].frame_bytes;
  if (static_cast<int>(frame->data.size()) > limit) {
    // Not in the spec: the fake refuses an over-size frame and keeps
    // waiting for one that fits (until DTO).
    later(config_.timing.echo, [this, limit] {
      report_error("NMEA", "4", "Frame longer than " + std::to_string(limit) + " bytes");
    });
    return;
  }
  accept_frame(*frame);
}

void FakeMicroModem::accept_frame(const TransmitData& frame) {
  Exchange& x = *exchange_;
  x.awaiting_frame = false;
  x.frames.push_back(DataFrame{frame.ack, frame.data});
  bool last = frame.data.empty() || static_cast<int>(x.frames.size()) >= x.frames_wanted;
  TransmitDataAccepted accepted{x.cycle.source, x.cycle.destination, frame.ack,
                                static_cast<int>(frame.data.size())};
  uint64_t id = x.id;
  later(config_.timing.echo, [this, accepted, last, id] {
    if (!exchange_ || exchange_->id != id) return;
    emit(to_sentence(accepted));
    if (last) {
      transmit_exchange();
    } else {
      request_frame();
    }
  });
}

void FakeMicroModem::data_timeout(uint64_t exchange_id, int frame) {
  if (!exchange_ || exchange_->id != exchange_id || !exchange_->awaiting_frame ||
      static_cast<int>(exchange_->frames.size()) + 1 != frame) {
    return;
  }
  exchange_->awaiting_frame = false;
  report_error("DATA_TIMEOUT", std::to_string(frame), "Data timeout");
  if (!exchange_->frames.empty()) return transmit_exchange();  // sends what it has
  // Nothing to send: no transmission, $CAXST mode 4 (§5.8).
  const Cycle& c = exchange_->cycle;
  AcousticPacket nothing{PacketKind::kData, c.rate, c.source, c.destination, c.ack,
                         exchange_->frames_wanted, {}, {}};
  exchange_.reset();
  transmit_statistics(nothing, 4, 0, 0);
}

void FakeMicroModem::transmit_exchange() {
  const Exchange& x = *exchange_;
  AcousticPacket packet{PacketKind::kData, x.cycle.rate, x.cycle.source, x.cycle.destination,
                        x.cycle.ack, x.frames_wanted, x.frames, {}};
  Duration air = data_air_time(x.cycle.rate, static_cast<int>(x.frames.size()));
  uint64_t id = x.id;
  later(std::chrono::milliseconds(nvram_.integer("TXD")), [this, packet, air, id] {
    if (!exchange_ || exchange_->id != id) return;
    transmit(packet, air, [this, id] {
      if (exchange_ && exchange_->id == id) exchange_.reset();
    });
  });
}

void FakeMicroModem::transmit(const AcousticPacket& packet, Duration air, std::function<void()> after) {
  int bytes = 2;  // every mini-packet reports 2 (§5.4)
  if (!packet.is_mini()) {
    bytes = 0;
    for (const DataFrame& frame : packet.frames) bytes += static_cast<int>(frame.bytes.size());
  }
  if (nvram_.flag("TXP")) emit(to_sentence(TransmitStarted{bytes}));
  transmitting_until_ = water_.scheduler().clock().now() + air;
  if (reception_) {  // half duplex: transmitting ends a reception
    reception_.reset();
    ++counters_.collisions;
  }
  ++counters_.transmissions;
  water_.transmit(this, packet, air);
  if (reboot_mid_transmission_ && !packet.is_mini()) {
    reboot_mid_transmission_ = false;
    later(air / 2, [this] { reboot(); });
  }
  later(air, [this, packet, bytes, after = std::move(after)] {
    if (nvram_.flag("TXF")) emit(to_sentence(TransmitFinished{bytes}));
    int frames = static_cast<int>(packet.frames.size());
    transmit_statistics(packet, 0, frames, packet.is_mini() ? 0 : bytes);
    after();
  });
}

void FakeMicroModem::transmit_statistics(const AcousticPacket& packet, int mode, int frames_sent,
                                         int bytes) {
  if (!nvram_.flag("XST")) return;
  bool mm1 = config_.generation == Generation::kMM1;
  bool psk = packet.is_psk(nvram_.flag("MOD"));
  TransmitStatistics s;
  s.version = mm1 ? 6 : 7;
  std::string stamp = modem_date_time(mm1 ? 4 : 6);
  s.date = stamp.substr(0, 8);
  s.time = stamp.substr(8);
  s.clock_status = clock_offset_ ? 1 : 0;
  s.mode = mode;
  s.probe_length = psk ? 200 : 40;
  s.bandwidth = nvram_.integer("BW0");
  s.carrier = nvram_.integer("FC0");
  s.rate = packet.rate;
  s.source = packet.source;
  s.destination = packet.destination;
  s.ack = packet.ack;
  s.frames_expected = packet.is_mini() ? 0 : packet.frames_wanted;
  s.frames_sent = frames_sent;
  s.packet_type = packet.kind == PacketKind::kFdp ? kPacketFdp
                  : packet.is_mini()                ? (psk ? kPacketPskMini : kPacketFskMini)
                                                    : (psk ? kPacketPsk : kPacketFsk);
  s.bytes = bytes;
  s.carrier_used = mm1 ? 0 : s.carrier;
  emit(to_sentence(s));
}

}  // namespace acomms::fake_micromodem
