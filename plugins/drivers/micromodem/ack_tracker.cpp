#include "micromodem/ack_tracker.h"

#include <spdlog/spdlog.h>

#include "core/core_thread.h"

namespace acomms::drivers::micromodem {

AckTracker::AckTracker(core::Scheduler& scheduler, int own_id,
                       std::function<void(const v1::ModemTransmission&)> deliver)
    : scheduler_(scheduler), own_id_(own_id), deliver_(std::move(deliver)) {}

AckTracker::~AckTracker() {
  if (timer_ != 0) scheduler_.cancel(timer_);
}

void AckTracker::expect(const v1::ModemTransmission& sent, std::chrono::system_clock::duration wait) {
  ACOMMS_ASSERT_CORE_THREAD();
  reset();
  if (sent.dest() <= 0 || !sent.ack_requested()) return;  // broadcasts are never acknowledged
  destination_ = sent.dest();
  rate_ = sent.rate();
  for (int i = 0; i < sent.frame_size(); ++i) {
    if (!sent.frame(i).empty()) awaited_.insert(i + 1);
  }
  if (awaited_.empty()) return;
  timer_ = scheduler_.after(wait, [this] {
    timer_ = 0;
    if (!awaited_.empty()) {
      ++counters_.expired;
      spdlog::debug("micromodem {}: {} frame(s) to {} not acknowledged in time", own_id_, awaited_.size(),
                    destination_);
    }
    flush();
    awaited_.clear();
  });
}

void AckTracker::on_ack(const ::acomms::micromodem::Acknowledgement& ack) {
  ACOMMS_ASSERT_CORE_THREAD();
  // Only the modem the data went to, for a frame still awaited (§10 quirks 8, 9).
  if (ack.destination != own_id_ || ack.source != destination_ || awaited_.count(ack.frame) == 0) {
    ++counters_.ignored;
    return;
  }
  ++counters_.accepted;
  awaited_.erase(ack.frame);
  batch_.insert(ack.frame);
}

void AckTracker::on_statistics() {
  ACOMMS_ASSERT_CORE_THREAD();
  flush();
  if (awaited_.empty() && timer_ != 0) {
    scheduler_.cancel(timer_);
    timer_ = 0;
  }
}

void AckTracker::flush() {
  if (batch_.empty()) return;
  v1::ModemTransmission ack;
  ack.set_type(v1::ModemTransmission::ACK);
  ack.set_src(destination_);
  ack.set_dest(own_id_);
  ack.set_rate(rate_);
  ack.set_ack_requested(false);
  for (int frame : batch_) ack.add_acked_frame(static_cast<uint32_t>(frame - 1));  // wire frames count from 1
  batch_.clear();
  deliver_(ack);
}

void AckTracker::reset() {
  if (timer_ != 0) scheduler_.cancel(timer_);
  timer_ = 0;
  awaited_.clear();
  batch_.clear();
  destination_ = -1;
}

}  // namespace acomms::drivers::micromodem
