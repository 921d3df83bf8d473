#include "link/rate_table.h"

namespace acomms::link {

namespace {
constexpr ModemRate kRates[] = {
    {0, 1, 32, 80},      // FH-FSK
    {1, 3, 64, 250},     // PSK
    {2, 3, 64, 500},     // PSK
    {3, 2, 256, 1200},   // PSK
    {4, 2, 256, 1300},   // PSK
    {5, 8, 256, 5300},   // PSK
};
}  // namespace

const ModemRate* find_rate(int32_t rate) {
  if (rate < kMinRate || rate > kMaxRate) return nullptr;
  return &kRates[rate];
}

std::chrono::nanoseconds packet_air_time(const ModemRate& rate, uint32_t num_frames) {
  // Integer nanoseconds so that tests on the simulated clock see exact times.
  uint64_t bits = uint64_t{num_frames} * rate.max_frame_bytes * 8;
  auto data = std::chrono::nanoseconds(static_cast<int64_t>(bits * 1'000'000'000ULL / rate.bits_per_second));
  return std::chrono::nanoseconds(kPacketHeader) + data;
}

}  // namespace acomms::link
