#include "micromodem/fdp_data_link.h"

#include <spdlog/spdlog.h>

#include "core/core_thread.h"
#include "link/rate_table.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;
using nmea::Sentence;
using v1::ModemTransmission;

namespace {

constexpr uint8_t kData = 0xDD;
constexpr uint8_t kAck = 0xDA;
constexpr uint32_t kHeader = 2;       // marker + ack_requested / count
constexpr uint32_t kFrameHeader = 2;  // a frame's length
constexpr uint32_t kPad = 1;          // room for the even-length pad
constexpr double kSlack = 2;          // serial time (as the data cycle's margin)

void pad_to_even(std::string* bytes) {
  if (bytes->size() % 2 != 0) *bytes += '\0';
}

std::string encode(const ModemTransmission& tx) {
  std::string out;
  if (tx.type() == ModemTransmission::ACK) {
    out += static_cast<char>(kAck);
    out += static_cast<char>(tx.acked_frame_size());
    for (uint32_t frame : tx.acked_frame()) out += static_cast<char>(frame);
  } else {
    out += static_cast<char>(kData);
    out += static_cast<char>(tx.ack_requested() ? 1 : 0);
    for (const std::string& frame : tx.frame()) {
      out += static_cast<char>(frame.size() >> 8);
      out += static_cast<char>(frame.size() & 0xFF);
      out += frame;
    }
  }
  pad_to_even(&out);
  return out;
}

}  // namespace

FdpDataLink::FdpDataLink(core::Scheduler& scheduler, CommandQueue& commands, int32_t own_id, double time_scale,
                         Hooks hooks)
    : scheduler_(scheduler), commands_(commands), own_id_(own_id), time_scale_(time_scale), hooks_(std::move(hooks)) {}

FdpDataLink::~FdpDataLink() { abort("the driver stopped"); }

uint32_t FdpDataLink::max_num_frames(int32_t rate) {
  const link::ModemRate* table = link::find_rate(rate);
  int limit = nmea::fdp_max_data_bytes(rate);
  if (table == nullptr || limit == 0) return 0;
  // The rate's frames, as many as fit the data section with their headers.
  uint32_t fit = (static_cast<uint32_t>(limit) - kHeader - kPad) / (table->max_frame_bytes + kFrameHeader);
  return std::min(fit, table->max_num_frames);
}

std::string FdpDataLink::send(const ModemTransmission& tx, bool report) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (current_) return "busy: an FDP packet is on the air";
  if (tx.type() == ModemTransmission::DATA && tx.frame_size() > 0 &&
      static_cast<uint32_t>(tx.frame_size()) > max_num_frames(tx.rate())) {
    return "rate " + std::to_string(tx.rate()) + " carries " + std::to_string(max_num_frames(tx.rate())) +
           " frames in an FDP packet (driver.micromodem.fdp_data), not " + std::to_string(tx.frame_size());
  }
  std::string payload = encode(tx);
  if (static_cast<int>(payload.size()) > nmea::fdp_max_data_bytes(tx.rate())) {
    return "an FDP packet at rate " + std::to_string(tx.rate()) + " carries at most " +
           std::to_string(nmea::fdp_max_data_bytes(tx.rate())) + " bytes (driver.micromodem.fdp_data), not " +
           std::to_string(payload.size());
  }
  current_.emplace(Current());
  current_->transmission = tx;
  current_->report = report;
  uint64_t generation = ++generation_;
  int rate = tx.rate();
  // No firmware ACK (§6): the ack field stays 0, the software ACK follows.
  commands_.push({nmea::to_sentence(nmea::FdpTransmit{static_cast<int>(tx.dest()), rate, false, payload}),
                  [](const Sentence& s) { return s.is("CATDP"); },
                  [this, generation, rate](bool ok, const Sentence* reply, const std::string& why) {
                    if (!current_ || generation != generation_) return;
                    if (!ok) return finish(false, "the modem did not take $CCTDP: " + why);
                    auto echo = nmea::parse_fdp_echo(*reply);
                    if (!echo || echo->error) {
                      return finish(false, "the modem refused the FDP packet ($CATDP " + std::string(reply->field(1)) + ")");
                    }
                    current_->on_air = true;
                    auto wait = std::chrono::duration<double>((nmea::fdp_packet_air_s(rate) + kSlack) / time_scale_);
                    current_->timer = scheduler_.after(
                        std::chrono::duration_cast<Duration>(wait), [this, generation] {
                          if (!current_ || generation != generation_) return;
                          current_->timer = 0;
                          finish(false, "no $CATXF (transmission finished) for the FDP packet in time");
                        });
                  },
                  1});
  return "";
}

bool FdpDataLink::on_transmit_finished() {
  if (!current_ || !current_->on_air) return false;
  finish(true, "");
  return true;
}

void FdpDataLink::finish(bool ok, const std::string& error) {
  if (!current_) return;
  Current done = std::move(*current_);
  current_.reset();
  if (done.timer != 0) scheduler_.cancel(done.timer);
  if (done.report) {
    if (hooks_.report) hooks_.report(done.transmission, ok, error);
  } else if (!ok) {
    spdlog::warn("micromodem {}: FDP acknowledgement not sent: {}", own_id_, error);
  }
}

void FdpDataLink::abort(const std::string& why) { finish(false, why); }

bool FdpDataLink::on_received(const nmea::FdpReceived& packet) {
  std::string payload = packet.payload();
  if (payload.size() < kHeader) return false;
  auto marker = static_cast<uint8_t>(payload[0]);
  if (marker != kData && marker != kAck) return false;
  if (!packet.intact()) return true;  // a frame failed its CRC: no ACK, the sender retries
  ModemTransmission rx;
  rx.set_src(packet.source);
  rx.set_dest(packet.destination);
  rx.set_rate(packet.rate);
  rx.set_time(hooks_.now_s());
  auto count = static_cast<uint8_t>(payload[1]);
  if (marker == kAck) {
    rx.set_type(ModemTransmission::ACK);
    if (payload.size() < kHeader + count) return true;  // cut short: not ours to guess
    for (uint32_t i = 0; i < count; ++i) rx.add_acked_frame(static_cast<uint8_t>(payload[kHeader + i]));
  } else {
    rx.set_type(ModemTransmission::DATA);
    rx.set_ack_requested(count != 0);
    size_t at = kHeader;
    while (payload.size() - at >= kFrameHeader) {
      size_t size = (static_cast<uint8_t>(payload[at]) << 8) | static_cast<uint8_t>(payload[at + 1]);
      at += kFrameHeader;
      if (payload.size() - at < size) return true;  // inconsistent lengths: dropped whole
      rx.add_frame(payload.substr(at, size));
      at += size;
    }
  }
  if (hooks_.received) hooks_.received(rx);
  return true;
}

}  // namespace acomms::drivers::micromodem
