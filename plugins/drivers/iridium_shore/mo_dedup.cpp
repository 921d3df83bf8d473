#include "iridium_shore/mo_dedup.h"

namespace acomms::drivers {

std::string MoDedup::key_of(std::string_view imei, uint16_t momsn, std::string_view payload) {
  // The whole payload is the key's tail (at most 340 bytes): no hash to
  // collide, and the IMEI has a fixed 15 digits, so the parts cannot blur.
  std::string key(imei);
  key += static_cast<char>(momsn >> 8);
  key += static_cast<char>(momsn & 0xff);
  key += payload;
  return key;
}

void MoDedup::forget_before(double cutoff) {
  while (!order_.empty() && order_.front().time < cutoff) {
    keys_.erase(order_.front().key);
    order_.pop_front();
  }
}

bool MoDedup::contains(std::string_view imei, uint16_t momsn, std::string_view payload, double now) {
  forget_before(now - window_s_);
  return keys_.count(key_of(imei, momsn, payload)) != 0;
}

void MoDedup::remember(std::string_view imei, uint16_t momsn, std::string_view payload, double now) {
  forget_before(now - window_s_);
  std::string key = key_of(imei, momsn, payload);
  if (!keys_.insert(key).second) return;
  while (order_.size() >= capacity_ && !order_.empty()) {
    keys_.erase(order_.front().key);
    order_.pop_front();
  }
  order_.push_back({now, std::move(key)});
}

}  // namespace acomms::drivers
