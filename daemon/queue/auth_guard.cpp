#include "queue/auth_guard.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/core_thread.h"

namespace acomms::queue {

std::string_view to_string(AuthRefusal refusal) {
  switch (refusal) {
    case AuthRefusal::kAuthFailed: return "auth_failed";
    case AuthRefusal::kReplayed: return "replayed";
    case AuthRefusal::kStale: return "stale";
  }
  return "?";
}

void AuthGuard::add_type(const std::string& type, double window_s) {
  if (!std::isfinite(window_s) || window_s <= 0) {
    throw std::invalid_argument("auth.type " + type + ": window_s must be more than 0 seconds (a window of " +
                                std::to_string(window_s) + " s would refuse every message as stale)");
  }
  if (!windows_.emplace(type, window_s).second) {
    throw std::invalid_argument("auth.type " + type + " is listed twice");
  }
}

double AuthGuard::window_s(const std::string& type) const {
  auto it = windows_.find(type);
  return it == windows_.end() ? 0 : it->second;
}

double AuthGuard::longest_window_s() const {
  double longest = 0;
  for (const auto& [type, w] : windows_) longest = std::max(longest, w);
  return longest;
}

std::string AuthGuard::key_of(const std::string& type, std::optional<int32_t> sender, std::string_view encoded) {
  // Type names hold no NUL; the sender is a fixed 5 bytes (a flag, then the
  // id), so no two (type, sender, bytes) make one key.
  std::string key = type;
  key.push_back('\0');
  key.push_back(sender ? '\1' : '\0');
  const auto id = static_cast<uint32_t>(sender.value_or(0));
  for (int i = 0; i < 4; ++i) key.push_back(static_cast<char>((id >> (8 * i)) & 0xff));
  key.append(encoded);
  return key;
}

std::optional<AuthRefusal> AuthGuard::judge(const std::string& type, int32_t sender, std::string_view encoded,
                                            const dccl::AuthStamp& stamp, double now) const {
  ACOMMS_ASSERT_CORE_THREAD();
  const double w = window_s(type);
  // Ahead as well as behind: a stamp in the future would otherwise be
  // remembered only until W past it, but accepted long before.
  if (std::fabs(now - static_cast<double>(stamp.sent_s)) > w) return AuthRefusal::kStale;
  if (seen_.count(key_of(type, sender, encoded)) > 0) return AuthRefusal::kReplayed;
  if (any_sender_seen_ && seen_.count(key_of(type, std::nullopt, encoded)) > 0) return AuthRefusal::kReplayed;
  return std::nullopt;
}

void AuthGuard::refuse(AuthRefusal why, const std::string& type, int32_t src, std::string_view detail, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  switch (why) {
    case AuthRefusal::kAuthFailed: ++refusals_.auth_failed; break;
    case AuthRefusal::kReplayed: ++refusals_.replayed; break;
    case AuthRefusal::kStale: ++refusals_.stale; break;
  }
  const bool new_burst = now - last_refusal_ > kBurstGapS;
  last_refusal_ = now;
  if (!new_burst) {
    ++in_burst_;
    return;
  }
  spdlog::warn("auth: {} message from {} refused ({}: {}), not delivered{}; further refusals within {} s of each "
               "other are only counted (acommsctl link status)",
               type, src, to_string(why), detail,
               in_burst_ > 0 ? " (" + std::to_string(in_burst_) + " more in the previous burst)" : std::string(),
               kBurstGapS);
  in_burst_ = 0;
}

void AuthGuard::remember(const std::string& type, int32_t sender, std::string_view encoded, uint32_t sent_s,
                         double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  std::string key = key_of(type, sender, encoded);
  if (seen_.insert(key).second) by_sent_.emplace(sent_s, std::move(key));
  forget(now);
}

void AuthGuard::forget(double now) {
  const double before = forget_before(now);
  while (!by_sent_.empty() && static_cast<double>(by_sent_.begin()->first) < before) {
    seen_.erase(by_sent_.begin()->second);
    by_sent_.erase(by_sent_.begin());
  }
}

void AuthGuard::refill(MessageJournal& journal, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (windows_.empty()) return;
  size_t remembered = 0;
  for (const QueueEvent& event : journal.authenticated_since(forget_before(now))) {
    if (!covers(event.type) || !event.auth_sent_s) continue;
    std::string key = key_of(event.type, event.auth_sender, event.encoded);
    any_sender_seen_ = any_sender_seen_ || !event.auth_sender;
    if (seen_.insert(key).second) {
      by_sent_.emplace(*event.auth_sent_s, std::move(key));
      ++remembered;
    }
  }
  spdlog::info("auth: {} accepted message{} remembered from the store, so that replays of them are refused",
               remembered, remembered == 1 ? "" : "s");
}

}  // namespace acomms::queue
