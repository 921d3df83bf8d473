#include "micromodem/data_cycle.h"

#include <spdlog/spdlog.h>

#include <cstdio>

#include "core/core_thread.h"
#include "link/rate_table.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;
using Duration = std::chrono::system_clock::duration;
using std::chrono::milliseconds;

namespace {

constexpr milliseconds kMiniAir{700};       // any mini-packet (§3.1: 0.5-0.7 s)
constexpr milliseconds kRequestAfter{500};  // $CACYC → $CADRQ for PSK (§9)
constexpr milliseconds kTurnaround{1000};   // decode + the destination's turnaround (§9: ~0.5-1 s)

std::string seconds_text(Duration d) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", std::chrono::duration<double>(d).count());
  return text;
}

std::string rate_error(int rate) {
  if (rate == 6) {
    return "rate 6 (PSK, 6 frames of 32 bytes) is valid on the Micro-Modem but not in acommsd's rate table "
           "(rates 0..5)";
  }
  return "rate " + std::to_string(rate) + " is not a Micro-Modem rate acommsd supports (0..5)";
}

const char* transmit_mode_text(int mode) {
  switch (mode) {
    case 1: return "FETs too hot";
    case 2: return "EXTSYNC timeout";
    case 3: return "transmit inhibited";
    case 4: return "data timeout, nothing sent";
    default: return "unknown mode";
  }
}

bool is_mini(int packet_type) {
  return packet_type == nmea::kPacketFskMini || packet_type == nmea::kPacketPskMini;
}

}  // namespace

DataCycle::DataCycle(core::Scheduler& scheduler, int own_id, CycleTimeouts timeouts, Hooks hooks)
    : scheduler_(scheduler), own_id_(own_id), timeouts_(timeouts), hooks_(std::move(hooks)) {}

DataCycle::~DataCycle() {
  if (timer_ != 0) scheduler_.cancel(timer_);
}

Duration DataCycle::scaled(Duration d) const {
  double scale = timeouts_.time_scale > 0 ? timeouts_.time_scale : 1;
  return std::chrono::duration_cast<Duration>(d / scale);
}

Duration DataCycle::air_time() const {
  const link::ModemRate* rate = link::find_rate(exchange_->cycle.rate);
  if (rate == nullptr) return std::chrono::seconds(7);
  // Every frame answered, blank ones too, is carried and costs a full
  // frame's time (§3, §5.3).
  int frames = std::max(1, exchange_->frames_answered);
  return std::chrono::duration_cast<Duration>(link::packet_air_time(*rate, static_cast<uint32_t>(frames)));
}

std::string DataCycle::start(const v1::ModemTransmission& tx, bool polled) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (phase_ != Phase::kIdle) return "busy: the modem is in another exchange";
  if (link::find_rate(tx.rate()) == nullptr) return rate_error(tx.rate());
  const link::ModemRate& rate = *link::find_rate(tx.rate());
  Exchange x;
  x.transmission = tx;
  if (polled) {
    x.kind = Kind::kPolled;
    // Nframes of the poll heard (the limit the queues were given).
    uint32_t frames = tx.max_num_frames() > 0 ? std::min(tx.max_num_frames(), rate.max_num_frames) : rate.max_num_frames;
    x.cycle = {0, own_id_, std::max(0, tx.dest()), tx.rate(), tx.ack_requested(), static_cast<int>(frames)};
  } else if (tx.src() != own_id_) {
    // Third-party cycle: node src sends to dest (us when the MAC left it open).
    x.kind = Kind::kPoll;
    // Nframes: what the MAC asked for when it said, else the rate's most.
    int frames = static_cast<int>(rate.max_num_frames);
    if (tx.max_num_frames() > 0 && tx.max_num_frames() < rate.max_num_frames) frames = static_cast<int>(tx.max_num_frames());
    x.cycle = {0, tx.src(), tx.dest() < 0 ? own_id_ : tx.dest(), tx.rate(), true, frames};
  } else {
    x.kind = Kind::kLocal;
    int dest = std::max(0, tx.dest());
    x.cycle = {0, own_id_, dest, tx.rate(), tx.ack_requested() && dest != 0, std::max(1, tx.frame_size())};
  }
  exchange_ = std::move(x);
  if (exchange_->kind == Kind::kPolled) {
    // The modem has the cycle already: its $CADRQ follows the poll's $CACST.
    phase_ = Phase::kSupplying;
    wait(kRequestAfter + timeouts_.margin, "$CADRQ");
    return "";
  }
  ++counters_.cycles;
  phase_ = Phase::kAwaitEcho;
  wait(timeouts_.echo, "$CACYC echo of $CCCYC");
  hooks_.write(to_sentence(exchange_->cycle, nmea::Talker::kHost));
  return "";
}

bool DataCycle::on_cycle(const nmea::Cycle& cycle) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (phase_ != Phase::kAwaitEcho) return false;
  const nmea::Cycle& ours = exchange_->cycle;
  if (cycle.source != ours.source || cycle.destination != ours.destination || cycle.rate != ours.rate) {
    // The modem is receiving someone else's cycle: ours will not run (§11).
    finish(false, "the modem is busy receiving (it printed $CACYC from " + std::to_string(cycle.source) +
                      " to " + std::to_string(cycle.destination) + ")");
    return false;
  }
  if (exchange_->kind == Kind::kPoll) {
    phase_ = Phase::kTransmitting;
    wait(kMiniAir + timeouts_.margin, "end of the poll's cycle-init ($CATXF)");
  } else {
    phase_ = Phase::kSupplying;
    // Rate 0 sends a cycle-init mini-packet before asking for data (§5.2).
    Duration until_request = ours.rate == 0 ? kMiniAir + kRequestAfter : Duration(kRequestAfter);
    wait(until_request + timeouts_.margin, "$CADRQ");
  }
  return true;
}

void DataCycle::on_data_request(const nmea::DataRequest& request) {
  ACOMMS_ASSERT_CORE_THREAD();
  bool ours = exchange_ && phase_ == Phase::kSupplying && exchange_->kind != Kind::kPoll &&
              request.source == exchange_->cycle.source;
  std::string data;
  if (ours) {
    const v1::ModemTransmission& tx = exchange_->transmission;
    int index = request.frame - 1;  // wire frames count from 1
    if (index >= 0 && index < tx.frame_size()) data = tx.frame(index);
    if (static_cast<int>(data.size()) > request.max_bytes) {
      spdlog::warn("micromodem {}: frame {} has {} bytes, the modem asks for at most {}: sent empty", own_id_,
                   request.frame, data.size(), request.max_bytes);
      data.clear();
    }
    ++exchange_->frames_answered;
    if (!data.empty()) {
      ++exchange_->frames_supplied;
      ++counters_.frames_supplied;
    }
    wait(kRequestAfter + timeouts_.margin, "$CADRQ or $CATXP after $CCTXD");
  } else {
    // A request we did not expect (a poll we could not serve, a stale
    // cycle): an empty frame ends it now rather than at DTO (§10 quirk 6).
    ++counters_.unsolicited_requests;
    spdlog::debug("micromodem {}: $CADRQ for frame {} outside an exchange: answered empty", own_id_,
                  request.frame);
  }
  hooks_.write(to_sentence(nmea::TransmitData{request.source, request.destination, request.ack, data}));
}

void DataCycle::on_transmit_started(const nmea::TransmitStarted& started) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!exchange_ || phase_ != Phase::kSupplying) return;
  if (exchange_->cycle.rate == 0 && exchange_->frames_supplied == 0 && started.bytes == 2) {
    // Rate 0's cycle-init mini-packet: the $CADRQ comes after it.
    wait(kMiniAir + kRequestAfter + timeouts_.margin, "$CADRQ after the cycle-init");
    return;
  }
  phase_ = Phase::kTransmitting;
  wait(air_time() + timeouts_.margin, "end of transmission ($CATXF)");
}

void DataCycle::on_transmit_finished(const nmea::TransmitFinished&) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!exchange_ || phase_ != Phase::kTransmitting) return;
  phase_ = Phase::kAwaitStatistics;
  wait(timeouts_.statistics, "$CAXST");  // without one (XST=0) the packet counts as sent
}

void DataCycle::on_transmit_statistics(const nmea::TransmitStatistics& statistics) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!exchange_ || phase_ == Phase::kAwaitEcho) return;
  if (statistics.mode != 0) {
    std::string why = "the modem did not transmit: $CAXST mode " + std::to_string(statistics.mode) + " (" +
                      transmit_mode_text(statistics.mode) + ")";
    if (!exchange_->data_timeout.empty()) why = exchange_->data_timeout;
    return finish(false, why);
  }
  bool mini = is_mini(statistics.packet_type);
  if (exchange_->kind == Kind::kPoll) {
    if (mini || statistics.packet_type == nmea::kPacketUnknown) finish(true, "");
    return;
  }
  if (mini) return;  // rate 0's cycle-init; the data packet's $CAXST follows
  finish(exchange_->data_timeout.empty(), exchange_->data_timeout);
}

void DataCycle::on_error(const nmea::ModemError& error) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (error.module == "DATA_TIMEOUT") {
    ++counters_.data_timeouts;
    if (exchange_ && exchange_->kind != Kind::kPoll) {
      // The modem sends what it has, or nothing ($CAXST mode 4): either
      // way this transmission did not go as asked.
      exchange_->data_timeout = "the modem's data request for frame " + error.number + " timed out ($CAERR DATA_TIMEOUT)";
    }
    return;
  }
  if (phase_ == Phase::kAwaitEcho) {
    finish(false, "the modem refused $CCCYC: " + error.module + " " + error.number + " " + error.message);
  }
}

void DataCycle::on_message(const nmea::TransactionMessage& message) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (exchange_ && message.type == "Transmit aborted") finish(false, "the modem aborted the transmission");
}

void DataCycle::abort(const std::string& why) {
  if (exchange_) finish(false, why);
}

void DataCycle::wait(Duration duration, const std::string& what) {
  if (timer_ != 0) scheduler_.cancel(timer_);
  Duration d = scaled(duration);
  timer_ = scheduler_.after(d, [this, what, d] {
    timer_ = 0;
    if (!exchange_) return;
    if (phase_ == Phase::kAwaitStatistics) return finish(exchange_->data_timeout.empty(), exchange_->data_timeout);
    finish(false, "no " + what + " within " + seconds_text(d));
  });
}

void DataCycle::finish(bool ok, const std::string& error) {
  if (timer_ != 0) scheduler_.cancel(timer_);
  timer_ = 0;
  Exchange x = std::move(*exchange_);
  exchange_.reset();
  phase_ = Phase::kIdle;
  if (!ok) ++counters_.failures;
  if (ok && x.kind != Kind::kPoll && hooks_.sent) {
    // The ACK comes after the range twice over, the turnaround and the ACK
    // mini-packet (§9); the data's air time is already behind us.
    Duration travel = std::chrono::duration_cast<Duration>(
        std::chrono::duration<double>(2 * timeouts_.max_range_m / 1500.0));
    hooks_.sent(x.transmission, scaled(travel + kTurnaround + kMiniAir + timeouts_.margin));
  }
  hooks_.report(x.transmission, ok, error);
}

}  // namespace acomms::drivers::micromodem
