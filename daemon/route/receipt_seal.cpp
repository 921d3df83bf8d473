// Sealed receipts (receipt_seal.h says why).
#include "route/receipt_seal.h"

#include <algorithm>
#include <cmath>

namespace acomms::route {

namespace {

constexpr double kSkewS = 60;

}  // namespace

void seal_receipt(std::string& bytes, const dccl::MessageAuthenticator* auth, double now) {
  if (auth != nullptr) auth->seal(bytes, now);
}

size_t sealed_size(size_t receipt_bytes, const dccl::MessageAuthenticator* auth) {
  return receipt_bytes + (auth != nullptr ? auth->trailer_bytes() : 0);
}

SealCheck check_receipt_seal(std::string_view rest, size_t receipt_bytes, const dccl::MessageAuthenticator* auth,
                             int32_t sender, double now, double window_s) {
  SealCheck check;
  const size_t want = sealed_size(receipt_bytes, auth);
  check.used = std::min(want, rest.size());
  if (auth == nullptr) return check;
  if (rest.size() < want) {
    check.ok = false;
    check.why = "no seal";
    return check;
  }
  dccl::AuthStamp stamp;
  const dccl::AuthVerdict verdict = auth->verify(rest.substr(0, want), now, sender, &stamp);
  if (verdict != dccl::AuthVerdict::kOk) {
    check.ok = false;
    check.why = std::string(dccl::to_string(verdict));
    return check;
  }
  const double sent = stamp.sent_s;
  if (!(sent >= now - window_s - kSkewS && sent <= now + kSkewS)) {
    check.ok = false;
    check.why = "stale (sealed " + std::to_string(static_cast<int64_t>(std::floor(now - sent))) + " s ago)";
  }
  return check;
}

}  // namespace acomms::route
