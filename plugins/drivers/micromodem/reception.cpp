#include "micromodem/reception.h"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "core/core_thread.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;

std::string describe_link_quality(const nmea::ReceiveStatistics& s) {
  char text[256];
  std::snprintf(text, sizeof text,
                "micromodem snr_in_db=%.1f snr_out_db=%.1f signal_level_db=%d mse_db=%.1f doppler=%.2f "
                "packet_type=%d bad_frames=%d psk_error=%d",
                s.snr_in, s.snr_out, s.spl, s.mse, s.doppler, s.packet_type, s.bad_frames, s.psk_error);
  return text;
}

v1::ReceptionFigures figures_of(const nmea::ReceiveStatistics& s) {
  v1::ReceptionFigures f;
  f.set_snr_in_db(s.snr_in);
  f.set_signal_level_db(s.spl);
  f.set_rss_db(s.rss);
  f.set_noise_db(s.noise);
  f.set_doppler_mps(s.doppler);
  f.set_packet_type(s.packet_type);
  f.set_frames(static_cast<uint32_t>(std::max(0, s.frames)));
  f.set_bad_frames(static_cast<uint32_t>(std::max(0, s.bad_frames)));
  bool psk = s.packet_type == nmea::kPacketPsk || s.packet_type == nmea::kPacketPskMini ||
             s.packet_type == nmea::kPacketFdp;
  if (psk) {
    // Equalizer figures mean nothing for FSK packets (the modem writes 0).
    f.set_snr_out_db(s.snr_out);
    f.set_snr_symbol_db(s.snr_symbol);
    f.set_mse_db(s.mse);
    f.set_psk_error(s.psk_error);
  } else {
    f.set_data_quality_factor(s.dqf);
  }
  return f;
}

Reception::Reception(int32_t own_id, std::function<double()> now_seconds, Deliver deliver)
    : own_id_(own_id), now_seconds_(std::move(now_seconds)), deliver_(std::move(deliver)) {}

Reception::Record& Reception::open() {
  // emplace(Record()), not emplace(): clang decides Record (nested, with a
  // default member initializer) is not default-constructible.
  if (!record_) record_.emplace(Record());
  return *record_;
}

void Reception::on_receive_started() {
  ACOMMS_ASSERT_CORE_THREAD();
  // A packet detected while another is unfinished: that one's $CACST is
  // not coming (CST=0, or a line lost); close it with what it has.
  if (record_) close(nullptr);
  record_.emplace(Record());
}

void Reception::on_cycle(const nmea::Cycle& cycle) {
  ACOMMS_ASSERT_CORE_THREAD();
  Record& record = open();
  // The second $CACYC of a PSK packet (its header) repeats the first.
  if (!record.cycle) record.cycle = cycle;
}

void Reception::on_data(const nmea::ReceivedData& frame) {
  ACOMMS_ASSERT_CORE_THREAD();
  Record& record = open();
  if (!record.first_frame) record.first_frame = frame;
  record.ack_requested = record.ack_requested || frame.ack;
  if (!frame.data.empty()) record.frames.push_back(frame.data);
}

void Reception::on_message(const nmea::TransactionMessage& message) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (message.is_bad_crc()) {
    // In place of a frame's $CARXD (or of a mini-packet): the frame is lost.
    ++counters_.bad_frames;
    ++open().bad_frames;
  } else if (message.is_packet_timeout()) {
    ++counters_.packet_timeouts;
  }
}

void Reception::on_statistics(const nmea::ReceiveStatistics& statistics) {
  ACOMMS_ASSERT_CORE_THREAD();
  ++counters_.packets;
  if (!record_ && statistics.mode == 2) {
    // Nothing was even detected: the packet a cycle-init announced, or our
    // poll asked for, never came.
    if (std::optional<Expected> from = announcer(true)) tell_lost(*from, nullptr);
    return;
  }
  close(&statistics);
}

std::optional<Reception::Expected> Reception::announcer(bool timeout) {
  std::optional<Announced> announced = std::exchange(announced_, std::nullopt);
  // The modem surely times out our own poll (§8.2); whether it does for a
  // cycle-init it only overheard the spec leaves open: a timeout is our
  // poll's first. A damaged packet is the one just announced.
  if (timeout && expected_) return expected_;
  if (announced && now_seconds_() - announced->heard_s <= kAnnouncementLife_s) return announced->packet;
  return expected_;
}

void Reception::note_cycle_init(const Record& record, const nmea::ReceiveStatistics& statistics) {
  const bool mini = statistics.packet_type == nmea::kPacketFskMini || statistics.packet_type == nmea::kPacketPskMini;
  if (!record.cycle || !mini || statistics.mode != 0) return;
  // ADR1 is the data's source (§5.1): ours is a poll of us, we send.
  if (record.cycle->source == own_id_) return;
  announced_ = Announced{{record.cycle->source, record.cycle->destination, record.cycle->rate}, now_seconds_()};
}

void Reception::tell_lost(const Expected& from, const nmea::ReceiveStatistics* figures) {
  if (expected_ && expected_->src == from.src) expected_.reset();
  ++counters_.lost_told;
  if (!on_failed_) return;
  v1::ModemTransmission lost;
  lost.set_type(v1::ModemTransmission::DATA);
  lost.set_src(from.src);
  lost.set_dest(from.dest);
  lost.set_rate(from.rate);
  lost.set_time(now_seconds_());
  if (figures != nullptr) *lost.mutable_figures() = figures_of(*figures);
  on_failed_(std::move(lost));
}

void Reception::close(const nmea::ReceiveStatistics* statistics) {
  if (!record_) return;
  Record record = std::move(*record_);
  record_.reset();
  if (record.frames.empty()) {
    // A cycle-init, an ACK, a blank, a damaged packet or a timeout; only
    // the damaged one and the one that never came are worth telling.
    if (statistics == nullptr) return;
    const bool damaged = statistics->mode == 1 || (record.bad_frames > 0 && statistics->mode != 2);
    if (!damaged && statistics->mode != 2) return note_cycle_init(record, *statistics);
    // A damaged mini-packet (a cycle-init or an ACK, BAD_CRC value 2) is no
    // data packet lost. It is the next packet, though: an announcement
    // heard before it is forgotten, or a cycle-init we could not read (of
    // another sender) would leave its data packet credited to the earlier
    // sender whose data never came.
    const bool mini = statistics->packet_type == nmea::kPacketFskMini || statistics->packet_type == nmea::kPacketPskMini;
    if (damaged && mini) {
      announced_.reset();
      return;
    }
    std::optional<Expected> from;
    if (record.cycle) {
      from = Expected{record.cycle->source, record.cycle->destination, record.cycle->rate};
      announced_.reset();
    } else {
      from = announcer(statistics->mode == 2);
    }
    if (!from) {
      if (damaged) ++counters_.unattributed;
      return;
    }
    tell_lost(*from, damaged ? statistics : nullptr);
    return;
  }
  announced_.reset();  // the packet it announced (or another) came
  if (expected_ && expected_->src == record.first_frame->source) expected_.reset();  // the answer came
  v1::ModemTransmission rx;
  rx.set_type(v1::ModemTransmission::DATA);
  // $CARXD names source and destination for each frame; the cycle's
  // (when heard) gives the rate.
  rx.set_src(record.first_frame->source);
  rx.set_dest(record.first_frame->destination);
  if (statistics != nullptr && statistics->mode != 2) {
    rx.set_rate(statistics->rate);
  } else if (record.cycle) {
    rx.set_rate(record.cycle->rate);
  }
  rx.set_ack_requested(record.ack_requested);
  for (std::string& frame : record.frames) rx.add_frame(std::move(frame));
  rx.set_time(now_seconds_());
  if (statistics != nullptr && statistics->mode != 2) {
    rx.set_link_quality(describe_link_quality(*statistics));
    *rx.mutable_figures() = figures_of(*statistics);
  }
  ++counters_.data_delivered;
  counters_.frames += static_cast<uint64_t>(rx.frame_size());
  deliver_(std::move(rx));
}

}  // namespace acomms::drivers::micromodem
