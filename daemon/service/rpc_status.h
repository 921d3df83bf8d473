#pragma once
// Answers several calls give alike, worded once so clients see one text.

#include <grpcpp/support/status.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace acomms::service {

// NOT_FOUND for a type name the codec does not know.
inline grpc::Status type_not_loaded(const std::string& type) {
  return {grpc::StatusCode::NOT_FOUND, "no DCCL type \"" + type + "\" is loaded"};
}

// NOT_FOUND for a type without a queue.
inline grpc::Status no_queue(const std::string& type) {
  return {grpc::StatusCode::NOT_FOUND, "no queue for type \"" + type + "\""};
}

// Listing calls (ListQueued, Events) answer at most this many items: 0 asks
// for the default, more than the most is refused. Sets *limit when OK.
inline grpc::Status page_limit(uint32_t requested, size_t* limit) {
  constexpr uint32_t kDefault = 1000;
  constexpr uint32_t kMost = 10000;
  if (requested > kMost) {
    return {grpc::StatusCode::INVALID_ARGUMENT, "limit is at most " + std::to_string(kMost)};
  }
  *limit = requested ? requested : kDefault;
  return grpc::Status::OK;
}

}  // namespace acomms::service
